#pragma once
/// \file sparse_surface_encoder.hpp
/// \brief Definitions of SparseSurfaceEncoder (encoder/sparse_surface_encoder.h).

#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/encoder/cloud_vertex_attributes.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/mesh/vertex_welding.h>
#include <pcl_sparse/model/attribute_gaps.h>
#include <pcl_sparse/patches/feature_aware_patch_sampling.h>
#include <pcl_sparse/surface/impl/surface_stage.hpp>

namespace pcl_sparse
{
  template <typename PointInT>
  void
  SparseSurfaceEncoder<PointInT>::compute (SparseSurfaceModel& model)
  {
    encoding_ = SurfaceEncoding ();
    attribute_gaps_ = AttributeGaps ();
    this->initCompute ();
    const std::string out_of_range = coordinateRangeProblem (*this->surface_, this->surface_origin_);
    if (!out_of_range.empty ())
      this->fail ("the " + std::string (this->surfaceIsScan () ? "scan's" : "mesh's") + " " + out_of_range);
    // Every face degenerate: no surface to code (rho bounds A_p / A with A = 0, normals are arbitrary).
    if (!hasSurfaceArea (*this->surface_))
      this->fail ("the mesh has no area: all " + std::to_string (this->surface_->triangles.size ()) +
                  " faces are degenerate");
    // Faces that share no vertex: no patch grows past its face (spot.obj through PCL's VTK reader, which
    // splits vertices with per-corner normals, gave 23062 patches without an atom, CR 1.44).
    if (isTriangleSoup (*this->surface_))
      this->fail ("the " + std::to_string (this->surface_->triangles.size ()) +
                  " faces share no vertex (a triangle soup, as PCL's VTK OBJ reader makes of a file with per-corner "
                  "normals), so no patch can grow past its face: weld the corners at equal positions first "
                  "(pcl_sparse::cleanMesh, weld_coincident_vertices) or load the file with pcl_sparse::loadPolygonMesh");
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
    SparseSurfaceEncoderOptions options = options_;
    if (this->surfaceIsScan () && options.scan_noise_floor && options.coding.noise_level == 0.0)
      options.coding.noise_level = this->cloud_surface_->noise;
    if (this->surfaceIsScan ())
    {
      options.coding.clip_footprints_at_holes = true;
      // A scan's triangles join noisy points: samples on them are that noise interpolated, and the code
      // follows it (the simulated plane scan of bench/scans.sh resampled 2x farther from the truth).
      options.coding.triangle_samples = 0.0;
      // Footprints reaching along smooth borders were measured on meshes only (bench/results/footprint_reach.md).
      options.coding.footprint_reach_degrees = 0.0;
      // A scan's codes stop at its noise floor already, and leaving atoms out was measured on meshes only
      // (bench/results/atom_loss.md).
      options.atom_loss_allowance = 0.0;
      // Drawing footprints in at flipped places was measured on meshes only (bench/results/flips.md): a
      // scan's triangles tilt with its noise, and its codes stop at the noise floor.
      options.trim_flipped_places = false;
    }
    options.patches = patchOptionsFor (options.patches, this->surfaceIsScan (), this->surfaceIsLidarRings ());
    VertexAttributes attributes = surfaceAttributes ();
    attribute_gaps_ = fillAttributeGaps (attributes, this->surface_->vertices);
    encoding_ = encodeSurface (*this->surface_, attributes, *this->surface_topology_, options, basis,
                               this->num_threads_, this->progress_, model, this->surfaceNormals (),
                               surfaceSeedVertices ());
    // A scan is encoded in its local frame: the model and patches go back to the input's frame.
    if (!this->surface_origin_.isZero (0.0))
    {
      model.translate (this->surface_origin_);
      for (Patch& patch : encoding_.patches)
        patch.origin += this->surface_origin_;
    }
  }

  template <typename PointInT>
  std::vector<std::uint8_t>
  SparseSurfaceEncoder<PointInT>::surfaceSeedVertices () const
  {
    std::vector<std::uint8_t> flags;
    if (!seed_vertices_)
      return flags;
    const std::size_t num_inputs =
        this->mesh_ ? this->mesh_->vertices.size () : this->scan_ ? this->scan_->size () : this->input_->size ();
    if (seed_vertices_->size () != num_inputs)
      this->fail ("setSeedVertices: " + std::to_string (seed_vertices_->size ()) + " flags for " +
                  std::to_string (num_inputs) + " input points");
    // Surface vertices as in surfaceAttributes.
    if (this->surfaceIsScan () && !this->scan_)
      for (std::size_t i : this->surface_input_indices_)
        flags.push_back ((*seed_vertices_)[i]);
    else if (!this->surfaceIsScan () && this->use_indices_ && this->indices_ && this->index_use_ == IndexUse::CropSurface)
      for (const auto i : *this->indices_)
        flags.push_back ((*seed_vertices_)[i]);
    else
      flags = *seed_vertices_;
    if (flags.size () != this->surface_->vertices.size ())
      this->fail ("the surface's vertices do not correspond to the input points: cannot carry the seed flags");
    return flags;
  }

  template <typename PointInT>
  VertexAttributes
  SparseSurfaceEncoder<PointInT>::surfaceAttributes () const
  {
    // The input initCompute used: a mesh (attributes only if set), a scan, or a cloud with or without polygons.
    VertexAttributes attributes;
    if (attributes_)
      attributes = *attributes_;
    else if (this->scan_ && !this->mesh_)
      attributes = scanVertexAttributes (*this->scan_);
    else if (this->input_ && !this->mesh_)
      attributes = cloudVertexAttributes (*this->input_);
    if (attributes.empty ())
      return attributes;
    const std::size_t num_inputs =
        this->mesh_ ? this->mesh_->vertices.size () : this->scan_ ? this->scan_->size () : this->input_->size ();
    if (static_cast<std::size_t> (attributes.values.rows ()) != num_inputs)
      this->fail ("setVertexAttributes: " + std::to_string (attributes.values.rows ()) + " rows for " +
                  std::to_string (num_inputs) + " input points");
    // Surface vertex v is: for a cloud without polygons, input point getSurfaceInputIndices ()[v]; for
    // setInputScan, scan point v; otherwise input point v, or indices[v] when setIndices crops.
    if (this->surfaceIsScan () && !this->scan_)
      attributes = attributes.selectRows (this->surface_input_indices_);
    else if (!this->surfaceIsScan () && this->use_indices_ && this->indices_ && this->index_use_ == IndexUse::CropSurface)
      attributes = attributes.selectRows (*this->indices_);
    if (static_cast<std::size_t> (attributes.values.rows ()) != this->surface_->vertices.size ())
      this->fail ("the surface's vertices do not correspond to the input points: cannot carry their attributes");
    return attributes;
  }
} // namespace pcl_sparse
