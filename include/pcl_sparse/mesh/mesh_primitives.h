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
  /// \param[in] nx, ny          cells along x and y
  /// \param[in] half_x, half_y  half extents of the grid
  /// \param[in] height          z as a function of (x, y)
  /// \return (nx + 1) (ny + 1) vertices, 2 nx ny triangles, counter-clockwise seen from +z
  TriangleMesh
  makeHeightFieldGrid (int nx, int ny, double half_x, double half_y, const std::function<double (double, double)>& height);

  /// Flat square [-half, half]^2 at z = 0.
  /// \param[in] n     cells per side
  /// \param[in] half  half the side length
  /// \return the grid, as makeHeightFieldGrid with z = 0
  TriangleMesh
  makePlaneGrid (int n, double half = 1.0);

  /// Open flat disk at z = 0 with nearly uniform edge lengths.
  /// \param[in] rings   concentric rings around the centre (ring k has 6 k vertices)
  /// \param[in] radius  radius of the outer ring
  /// \return the disk, counter-clockwise seen from +z
  TriangleMesh
  makeDisk (int rings, double radius = 1.0);

  /// Icosphere: the icosahedron subdivided, vertices projected to the sphere.
  /// \param[in] subdivisions  s, number of subdivisions: 10 * 4^s + 2 vertices
  /// \param[in] radius        sphere radius
  /// \param[in] center        sphere centre
  /// \return the closed sphere, outward faces
  TriangleMesh
  makeIcosphere (int subdivisions, double radius = 1.0, const Eigen::Vector3d& center = Eigen::Vector3d::Zero ());

  /// Closed axis-aligned cube [-half, half]^3 (welded, watertight).
  /// \param[in] n     cells per side of each face
  /// \param[in] half  half the side length
  /// \return the cube, outward faces
  TriangleMesh
  makeCube (int n, double half = 1.0);

  /// Open cylinder around the z axis, z in [-half_height, half_height].
  /// \param[in] around       vertices per ring
  /// \param[in] along        cells along z
  /// \param[in] radius       cylinder radius
  /// \param[in] half_height  half its length
  /// \return the cylinder (two boundary loops), outward faces
  TriangleMesh
  makeCylinder (int around, int along, double radius = 1.0, double half_height = 1.0);

  /// Torus around the z axis (genus 1).
  /// \param[in] major_segments  segments around the z axis
  /// \param[in] minor_segments  segments around the tube
  /// \param[in] major_radius    R, distance from the axis to the tube's centre line
  /// \param[in] minor_radius    r, radius of the tube
  /// \return the closed torus, outward faces
  TriangleMesh
  makeTorus (int major_segments, int minor_segments, double major_radius = 1.0, double minor_radius = 0.3);

  /// Regular tetrahedron inscribed in the unit sphere.
  TriangleMesh
  makeTetrahedron ();

  /// Appends one mesh to another (disjoint union).
  /// \param[in,out] mesh   receives the vertices and triangles of \a other
  /// \param[in]     other  the mesh appended; its indices are shifted by the vertex count of \a mesh
  void
  appendMesh (TriangleMesh& mesh, const TriangleMesh& other);
} // namespace pcl_sparse
