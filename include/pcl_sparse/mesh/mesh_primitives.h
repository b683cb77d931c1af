#pragma once
/// \file mesh_primitives.h
/// Analytic test surfaces as triangle meshes: known curvature, known features, known topology.
/// Used by the tests and handy for users checking a pipeline. All faces are counter-clockwise seen
/// from outside (closed surfaces) or from +z (height fields).

#include <pcl_sparse/mesh/triangle_mesh.h>

#include <functional>

namespace pcl_sparse
{
  /// Height field z = height(x, y) sampled on a regular (nx + 1) x (ny + 1) grid over
  /// [-half_x, half_x] x [-half_y, half_y]; each grid cell is split into two triangles along alternating
  /// diagonals (so the mesh has no preferred direction).
  TriangleMesh
  makeHeightFieldGrid (int nx, int ny, double half_x, double half_y, const std::function<double (double, double)>& height);

  /// Flat square [-half, half]^2 at z = 0, n x n cells.
  TriangleMesh
  makePlaneGrid (int n, double half = 1.0);

  /// Open flat disk of the given radius at z = 0, built from \a rings concentric rings (6 k vertices on
  /// ring k), so edge lengths are nearly uniform.
  TriangleMesh
  makeDisk (int rings, double radius = 1.0);

  /// Icosphere: the icosahedron subdivided \a subdivisions times, vertices projected to the sphere.
  /// 10 * 4^s + 2 vertices.
  TriangleMesh
  makeIcosphere (int subdivisions, double radius = 1.0, const Eigen::Vector3d& center = Eigen::Vector3d::Zero ());

  /// Closed axis-aligned cube [-half, half]^3, each face an n x n grid (welded, watertight).
  TriangleMesh
  makeCube (int n, double half = 1.0);

  /// Open cylinder of the given radius around the z axis, z in [-half_height, half_height];
  /// \a around vertices per ring, \a along cells in z.
  TriangleMesh
  makeCylinder (int around, int along, double radius = 1.0, double half_height = 1.0);

  /// Torus around the z axis with major radius R and minor radius r (genus 1).
  TriangleMesh
  makeTorus (int major_segments, int minor_segments, double major_radius = 1.0, double minor_radius = 0.3);

  /// Regular tetrahedron inscribed in the unit sphere.
  TriangleMesh
  makeTetrahedron ();

  /// Appends \a other to \a mesh (disjoint union; indices of \a other are shifted).
  void
  appendMesh (TriangleMesh& mesh, const TriangleMesh& other);
} // namespace pcl_sparse
