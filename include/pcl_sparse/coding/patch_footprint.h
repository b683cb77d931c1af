#pragma once
/// \file patch_footprint.h
/// The region of its tangent plane where a patch has data (PatchFootprint), from the patch's triangles.

#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/patches/patch.h>

namespace pcl_sparse
{
  /// Star-shaped footprint covering the patch's own triangles projected on its tangent plane (local
  /// x', y'), and its vertices.
  /// \param[in] patch   frame, radius and local coordinates set
  /// \param[in] mesh    the mesh
  /// \param[in] angles  K, the number of extents (equally spaced angles)
  /// \return the footprint
  ///
  /// Choice: the exact maximum radius of the projected triangles inside each angular sector
  /// [2 pi k / K, 2 pi (k + 1) / K) is found from their edges (|p| is convex along a segment, so the
  /// maximum over a segment clipped to a sector is at a clip point: an endpoint or a crossing of a sector
  /// ray). Extent k is the larger of the two sector maxima adjacent to angle k, so the linear
  /// interpolation of PatchFootprint never cuts a triangle: every point of every projected triangle
  /// satisfies footprint.contains() (it may also admit a little outside, never less). A projected
  /// triangle containing the origin cannot exceed its edges' radii, so edges suffice.
  ///
  /// With \a clip_at_first_exit (scans), extent k is also at most the radius where ray k first leaves the
  /// union of the projected triangles for a gap wider than 3 median edge lengths before meeting them again:
  /// a patch that grew around a hole of the scan (a shadow, missing depth) or along a concave border then
  /// does not cover it, while a missing triangle here and there does not cut it short. Points of the
  /// triangles beyond such an exit are left to the patches around them.
  /// \param[in] clip_at_first_exit  clip the extents as above (default false: the exact cover)
  ///
  /// With \a clip_at_border (ours, the encoder's default), extent k is first lowered to the outermost
  /// radius where ray k crosses the border of the union of the projected triangles (an edge of one
  /// triangle only), then the two extents around each corner the interpolation would cut are raised just
  /// enough to hold it (never above the sector maxima). Every point of every projected triangle is still
  /// inside (along a segment within one sector the radius is a convex function of the angle, so holding
  /// its ends, corners or ray crossings, holds it), but the footprint no longer reaches the farthest
  /// corner between two rays where the border runs closer: at open borders and sharp edges that overshoot
  /// is where a code extrapolates past the surface, on a thin part to its other side, and resampled
  /// normals there point the wrong way.
  /// \param[in] clip_at_border  clip the extents as above (default false: the sector maxima)
  ///
  /// With clip_at_border and \a topology, where a ray's outermost border crossing is an edge past which the
  /// surface goes on smoothly (the face beyond it tilted at most \a reach_max_tilt_degrees from the patch's
  /// normal), its extent is then raised towards the largest extent within \a reach_degrees on either side
  /// whose ray also leaves across such an edge, by at most half the median edge length. Inside the surface
  /// a patch's border is the zigzag of its triangles' outer corners, and the clipped footprint followed
  /// it, leaving slivers between the corners to patches that fit them worse; the code goes on fitting a
  /// little past its triangles there. At open borders and sharp edges the footprint stays clipped; the cap
  /// keeps the long corners of coarse CAD meshes' thin triangles from spreading (turbine's Chamfer distance
  /// 39 % larger without it).
  /// \param[in] reach_degrees  how far along the border an extent reaches (0: not at all)
  /// \param[in] topology  the mesh's (nullptr: no reach)
  /// \param[in] reach_max_tilt_degrees  largest tilt of the face beyond a border edge the reach goes over
  PatchFootprint
  computePatchFootprint (const Patch& patch, const TriangleMesh& mesh, int angles = 16,
                         bool clip_at_first_exit = false, bool clip_at_border = false,
                         double reach_degrees = 0.0, const MeshTopology* topology = nullptr,
                         double reach_max_tilt_degrees = 20.0);
} // namespace pcl_sparse
