#pragma once
/// \file surface_stage.hpp
/// \brief Definitions of SurfaceStage (surface/surface_stage.h); included by the library for the common point
/// types, and by programs that define PCL_NO_PRECOMPILE for others.

#include <pcl_sparse/io/scan_conversion.h>
#include <pcl_sparse/mesh/mesh_report.h>
#include <pcl_sparse/mesh/polygon_faces.h>
#include <pcl_sparse/mesh/sub_mesh.h>
#include <pcl_sparse/surface/surface_stage.h>

#include <pcl/common/io.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace pcl_sparse
{
  template <typename PointInT>
  void
  SurfaceStage<PointInT>::initCompute ()
  {
    deinitCompute ();
    surface_.reset ();
    surface_origin_.setZero ();
    cloud_surface_.reset ();
    cleaning_report_ = ScanCleaningReport ();
    surface_input_indices_.clear ();
    duplicate_faces_ = 0;
    repeated_corner_faces_ = 0;
    const std::string where = "[" + getClassName () + "::compute] ";
    const bool has_indices = this->use_indices_ && this->indices_;
    const bool use_indices = has_indices && index_use_ == IndexUse::CropSurface;
    if (use_indices && this->indices_->empty ())
      fail ("setIndices: the indices are empty, so the crop holds no surface");
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
    else if (scan_ || (this->input_ && !polygons_))
    {
      // A scan given as such is already the part to work on: crop it before (indices select points of a
      // cloud or vertices of a mesh).
      if (scan_ && use_indices)
        fail ("setIndices crops a cloud (setInputCloud) or a mesh (setInputMesh), not a scan (setInputScan): "
              "crop the scan itself");
      initScanSurface ();
      if (surface_->triangles.empty ())
        fail ("the scan gives no surface: none of its " + std::to_string (surface_->vertices.size ()) +
              " points has neighbours close enough to make a triangle");
    }
    else
    {
      if (!this->input_)
        fail ("no input: setInputCloud (with setInputPolygons for a mesh), setInputMesh or setInputScan");
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
      // The points of the input cloud, or the vertices of the surface (a mesh's, or a scan's points).
      const std::size_t num_points = surfaceIsScan () && this->input_ ? this->input_->size () : surface_->vertices.size ();
      for (const auto v : *this->indices_)
        if (v < 0 || static_cast<std::size_t> (v) >= num_points)
          fail ("setIndices: index " + std::to_string (v) + " out of range (" + std::to_string (num_points) + " points)");
      selected_ = this->indices_;
    }
    if (!surfaceIsScan ())
      dropFacesWithoutSurface ();
    if (surface_->vertices.empty () || surface_->triangles.empty ())
      fail ("no input mesh or an empty one (set a mesh with triangles)");
    if (!surface_topology_)
      surface_topology_ = std::make_shared<const MeshTopology> (buildMeshTopology (*surface_, num_threads_));
  }

  template <typename PointInT>
  void
  SurfaceStage<PointInT>::dropFacesWithoutSurface ()
  {
    const std::vector<int> first_copy = findDuplicateFaces (*surface_);
    std::vector<std::uint8_t> kept (first_copy.size (), 1);
    std::size_t copies = 0, repeated_corners = 0;
    for (std::size_t f = 0; f < first_copy.size (); ++f)
    {
      const Eigen::Vector3i& t = surface_->triangles[f];
      if (hasRepeatedIndex (t))
        ++repeated_corners, kept[f] = 0;
      else if (first_copy[f] != static_cast<int> (f))
        ++copies, kept[f] = 0;
    }
    if (copies + repeated_corners == 0)
      return;
    if (copies + repeated_corners == first_copy.size ())
      fail ("the mesh has no area: every one of its " + std::to_string (first_copy.size ()) +
            " faces repeats a corner or an earlier face");
    auto unique = std::make_shared<TriangleMesh> ();
    unique->vertices = surface_->vertices;
    unique->triangles.reserve (first_copy.size () - copies - repeated_corners);
    for (std::size_t f = 0; f < first_copy.size (); ++f)
      if (kept[f])
        unique->triangles.push_back (surface_->triangles[f]);
    surface_ = std::move (unique);
    surface_topology_.reset ();  // a topology given with setTopology counts the faces left out
    duplicate_faces_ = copies;
    repeated_corner_faces_ = repeated_corners;
  }

  template <typename PointInT>
  void
  SurfaceStage<PointInT>::initScanSurface ()
  {
    ScanCloud::ConstPtr scan = scan_;
    if (!scan)
    {
      // A cloud without polygons: cleaned into a scan; CropSurface indices select the points it is built from.
      const bool crop = this->use_indices_ && this->indices_ && index_use_ == IndexUse::CropSurface;
      auto built = std::make_shared<ScanCloud> ();
      if (crop)
      {
        for (const auto v : *this->indices_)
          if (v < 0 || static_cast<std::size_t> (v) >= this->input_->size ())
            fail ("setIndices: index " + std::to_string (v) + " out of range (" + std::to_string (this->input_->size ()) +
                  " points)");
        // The points in index order, unorganized. Not pcl::copyPointCloud: given as many indices as points it
        // copies the whole cloud as it is, whatever their order, and the indices below mapped its points to
        // other points (an organized cloud's pixels were scrambled).
        PointCloudIn subset;
        subset.header = this->input_->header;
        subset.sensor_origin_ = this->input_->sensor_origin_;
        subset.sensor_orientation_ = this->input_->sensor_orientation_;
        subset.resize (this->indices_->size ());
        for (std::size_t i = 0; i < this->indices_->size (); ++i)
          subset[i] = (*this->input_)[static_cast<std::size_t> ((*this->indices_)[i])];
        subset.is_dense = this->input_->is_dense;
        toScanCloud (subset, *built, cleaning_options_);
        for (std::size_t& index : built->indices)
          index = static_cast<std::size_t> ((*this->indices_)[index]);
      }
      else
        toScanCloud (*this->input_, *built, cleaning_options_);
      if (built->size () == 0)
        fail ("the cloud has no usable point: all " + std::to_string (built->report.input_points) +
              " are non-finite, duplicates or at the sensor origin");
      scan = built;
    }
    CloudSurfaceOptions options = cloud_options_;
    options.num_threads = num_threads_;
    // A merged scan's per-point viewpoints (vp_x vp_y vp_z), unless the caller gave viewpoints of its own.
    if (options.point_viewpoints.empty () && !options.has_viewpoint && !scan->viewpoints.empty ())
      options.point_viewpoints = scan->viewpoints;
    CloudSurface surface = buildCloudSurface (*scan, options);
    surface_ = std::make_shared<const TriangleMesh> (std::move (surface.mesh));
    surface.mesh = TriangleMesh ();
    cloud_surface_ = std::make_shared<const CloudSurface> (std::move (surface));
    surface_origin_ = scan->origin;
    cleaning_report_ = scan->report;
    surface_input_indices_ = scan->indices;
  }
  template <typename PointInT>
  std::vector<int>
  SurfaceStage<PointInT>::selectedSurfaceVertices () const
  {
    std::vector<int> vertices;
    if (!selected_)
      return vertices;
    for (int v : outputVertices ())
      if (v >= 0)
        vertices.push_back (v);
    return vertices;
  }

  template <typename PointInT>
  std::vector<int>
  SurfaceStage<PointInT>::outputVertices () const
  {
    if (!surfaceIsScan () || !this->input_)
    {
      if (selected_)
        return std::vector<int> (selected_->begin (), selected_->end ());
      std::vector<int> all (surface_->vertices.size ());
      for (std::size_t v = 0; v < all.size (); ++v)
        all[v] = static_cast<int> (v);
      return all;
    }
    std::vector<int> vertex_of_point (this->input_->size (), -1);
    for (std::size_t v = 0; v < surface_input_indices_.size (); ++v)
      vertex_of_point[surface_input_indices_[v]] = static_cast<int> (v);
    if (cleaning_report_.duplicates_merged > 0)
      mapDuplicatesToTheirKeptPoint (vertex_of_point);
    if (!selected_)
      return vertex_of_point;
    std::vector<int> rows;
    rows.reserve (selected_->size ());
    for (const auto point : *selected_)
      rows.push_back (vertex_of_point[point]);
    return rows;
  }

  template <typename PointInT>
  void
  SurfaceStage<PointInT>::mapDuplicatesToTheirKeptPoint (std::vector<int>& vertex_of_point) const
  {
    // Cleaning keeps the first of each run of equal positions; the others stand at the same place, so they
    // take its vertex (they were left with none, and got NaN normals: half of a scan stored twice).
    using Position = std::array<float, 3>;
    std::vector<std::pair<Position, int>> kept;
    kept.reserve (surface_input_indices_.size ());
    for (std::size_t v = 0; v < surface_input_indices_.size (); ++v)
    {
      const PointInT& p = (*this->input_)[surface_input_indices_[v]];
      kept.push_back ({Position{p.x, p.y, p.z}, static_cast<int> (v)});
    }
    const auto by_position = [] (const std::pair<Position, int>& a, const std::pair<Position, int>& b) {
      return a.first < b.first;  // -0 and 0 are one position, as in cleaning
    };
    std::sort (kept.begin (), kept.end (), by_position);
    for (std::size_t i = 0; i < vertex_of_point.size (); ++i)
    {
      const PointInT& p = (*this->input_)[i];
      if (vertex_of_point[i] >= 0 || !std::isfinite (p.x) || !std::isfinite (p.y) || !std::isfinite (p.z))
        continue;
      const std::pair<Position, int> probe{Position{p.x, p.y, p.z}, -1};
      const auto twin = std::lower_bound (kept.begin (), kept.end (), probe, by_position);
      if (twin != kept.end () && !by_position (probe, *twin))
        vertex_of_point[i] = twin->second;
    }
  }

  template <typename PointInT>
  Eigen::Vector3d
  SurfaceStage<PointInT>::outputPosition (std::size_t row, int vertex) const
  {
    if (surfaceIsScan () && this->input_)
    {
      const PointInT& p = (*this->input_)[selected_ ? static_cast<std::size_t> ((*selected_)[row]) : row];
      return Eigen::Vector3d (p.x, p.y, p.z);
    }
    return surface_origin_ + surface_->vertices[vertex];
  }
} // namespace pcl_sparse
