#pragma once
/// \file sparse_surface_encoder.hpp
/// \brief Definitions of SparseSurfaceEncoder (encoder/sparse_surface_encoder.h).

#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/encoder/cloud_vertex_attributes.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/mesh/impl/surface_stage.hpp>

namespace pcl_sparse
{
  template <typename PointInT>
  void
  SparseSurfaceEncoder<PointInT>::compute (SparseSurfaceModel& model)
  {
    encoding_ = SurfaceEncoding ();
    this->initCompute ();
    // Every face degenerate: no surface to code (rho bounds A_p / A with A = 0, normals are arbitrary).
    if (!hasSurfaceArea (*this->surface_))
      this->fail ("the mesh has no area: all " + std::to_string (this->surface_->triangles.size ()) +
                  " faces are degenerate");
    options_.validate ();
    computeModel (model);
    this->deinitCompute ();
  }

  template <typename PointInT>
  void
  SparseSurfaceEncoder<PointInT>::computeModel (SparseSurfaceModel& model)
  {
    const SurfaceBasis::ConstPtr basis =
      basis_ ? basis_ : makeCosineBasis (options_.basis, options_.dictionary_frequencies);
    const VertexAttributes attributes = surfaceAttributes ();
    encoding_ = encodeSurface (*this->surface_, attributes, *this->surface_topology_, options_, basis,
                               this->num_threads_, this->progress_, model);
  }

  template <typename PointInT>
  VertexAttributes
  SparseSurfaceEncoder<PointInT>::surfaceAttributes () const
  {
    VertexAttributes attributes;
    if (attributes_)
      attributes = *attributes_;
    else if (this->input_ && !this->mesh_)
      attributes = cloudVertexAttributes (*this->input_);
    if (attributes.empty ())
      return attributes;
    const std::size_t num_inputs = this->mesh_ ? this->mesh_->vertices.size () : this->input_->size ();
    if (static_cast<std::size_t> (attributes.values.rows ()) != num_inputs)
      this->fail ("setVertexAttributes: " + std::to_string (attributes.values.rows ()) + " rows for " +
                  std::to_string (num_inputs) + " input points");
    // Surface vertex i is input point i, or indices[i] when setIndices crops (SurfaceStage::initCompute).
    if (this->use_indices_ && this->indices_ && this->index_use_ == IndexUse::CropSurface)
      attributes = attributes.selectRows (*this->indices_);
    if (static_cast<std::size_t> (attributes.values.rows ()) != this->surface_->vertices.size ())
      this->fail ("the surface's vertices do not correspond to the input points: cannot carry their attributes");
    return attributes;
  }
} // namespace pcl_sparse
