#pragma once
/// \file surface_stage.hpp
/// \brief Definitions of SurfaceStage (mesh/surface_stage.h); included by the library for the common point
/// types, and by programs that define PCL_NO_PRECOMPILE for others.

#include <pcl_sparse/mesh/polygon_faces.h>
#include <pcl_sparse/mesh/sub_mesh.h>
#include <pcl_sparse/mesh/surface_stage.h>

namespace pcl_sparse
{
  template <typename PointInT>
  void
  SurfaceStage<PointInT>::initCompute ()
  {
    deinitCompute ();
    const std::string where = "[" + getClassName () + "::compute] ";
    const bool has_indices = this->use_indices_ && this->indices_;
    const bool use_indices = has_indices && index_use_ == IndexUse::CropSurface;
    if (mesh_)
    {
      for (const Eigen::Vector3i& t : mesh_->triangles)
        for (int k = 0; k < 3; ++k)
          if (t[k] < 0 || static_cast<std::size_t> (t[k]) >= mesh_->vertices.size ())
            fail ("face index " + std::to_string (t[k]) + " out of range (" + std::to_string (mesh_->vertices.size ()) +
                  " vertices)");
      surface_ = use_indices ? std::make_shared<const TriangleMesh> (extractSubMesh (*mesh_, *this->indices_, where + "setIndices"))
                             : mesh_;
      if (!use_indices && topology_)
      {
        if (topology_->numVertices () != mesh_->numVertices ())
          fail ("the topology (setTopology) does not belong to the input mesh");
        surface_topology_ = topology_;
      }
    }
    else
    {
      if (!this->input_)
        fail ("no input: setInputCloud and setInputPolygons, or setInputMesh");
      if (!polygons_)
        fail ("the input cloud has no polygons (setInputPolygons): point clouds without faces are not supported yet");
      TriangleMesh whole;
      whole.vertices = cloudPositions (*this->input_);
      whole.triangles = trianglesFromPolygons (*polygons_, whole.vertices.size (), where + "setInputPolygons");
      for (const Eigen::Vector3i& t : whole.triangles)
        for (int k = 0; k < 3; ++k)
          if (!whole.vertices[t[k]].allFinite ())
            fail ("polygon corner " + std::to_string (t[k]) + " is not a finite point");
      surface_ = std::make_shared<const TriangleMesh> (
        use_indices ? extractSubMesh (whole, *this->indices_, where + "setIndices") : std::move (whole));
    }
    if (has_indices && !use_indices)
    {
      const std::size_t num_points = surface_->vertices.size ();
      for (const auto v : *this->indices_)
        if (v < 0 || static_cast<std::size_t> (v) >= num_points)
          fail ("setIndices: index " + std::to_string (v) + " out of range (" + std::to_string (num_points) + " points)");
      selected_ = this->indices_;
    }
    if (surface_->vertices.empty () || surface_->triangles.empty ())
      fail ("no input mesh or an empty one (set a mesh with triangles)");
    if (!surface_topology_)
      surface_topology_ = std::make_shared<const MeshTopology> (buildMeshTopology (*surface_));
  }
} // namespace pcl_sparse
