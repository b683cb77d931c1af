#include <pcl_sparse/tiles/memory_tile_source.h>

#include <pcl_sparse/cloud/depth_quantization.h>
#include <pcl_sparse/cloud/scan_grid.h>
#include <pcl_sparse/cloud/sensor_evidence.h>
#include <pcl_sparse/common/error.h>

#include <limits>

namespace pcl_sparse
{
  namespace
  {
    /// Copies entry \a i of \a from to the end of \a to when \a from has one per point.
    template <typename T>
    void
    copyIfPresent (const std::vector<T>& from, std::size_t i, std::vector<T>& to)
    {
      if (!from.empty ())
        to.push_back (from[i]);
    }
  } // namespace

  MemoryTileSource::MemoryTileSource (const ScanCloud::ConstPtr& scan, const TileGridOptions& options) : scan_ (scan)
  {
    if (!scan || scan->size () == 0)
      throw Error ("MemoryTileSource: " + (scan ? scan->report : ScanCleaningReport ()).emptyScanMessage ());
    cut (worldPositions (*scan), options);
    // Judged once on every point: a tile's part of them cannot tell (its distances vary too little).
    std::vector<std::uint8_t> finite (scan->size ());
    for (std::size_t i = 0; i < scan->size (); ++i)
      finite[i] = scan->positions[i].allFinite () ? 1 : 0;
    sensor_pose_ = scan->has_sensor_pose && !defaultPoseIsUnsupported (*scan, finite);
    SteppedAxes steps (scan->size ());
    for (std::size_t i = 0; i < scan->size (); ++i)
      steps.add (scan->worldPosition (i));
    stepped_axes_ = steps.judge (scan->size ());
  }

  MemoryTileSource::MemoryTileSource (const TriangleMesh::ConstPtr& mesh, const TileGridOptions& options) : mesh_ (mesh)
  {
    if (!mesh || mesh->vertices.empty ())
      throw Error ("MemoryTileSource: the mesh has no vertices");
    cut (mesh->vertices, options);
  }

  void
  MemoryTileSource::cut (const std::vector<Eigen::Vector3d>& world, const TileGridOptions& options)
  {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : world)
    {
      if (!p.allFinite ())
        throw Error ("MemoryTileSource: a point is not finite");
      box.extend (p);
    }
    grid_ = makeTileGrid (box, world.size (), options);
    if (grid_.size () > std::numeric_limits<std::uint32_t>::max ())
      throw Error ("MemoryTileSource: too many tiles (" + std::to_string (grid_.size ()) + ")");
    tile_of_.resize (world.size ());
    core_counts_.assign (grid_.size (), 0);
    for (std::size_t i = 0; i < world.size (); ++i)
    {
      tile_of_[i] = static_cast<std::uint32_t> (grid_.tileOf (world[i]));
      ++core_counts_[tile_of_[i]];
    }
  }

  bool
  MemoryTileSource::inMargin (std::size_t i, const Eigen::AlignedBox3d& box) const
  {
    return box.contains (scan_ ? scan_->worldPosition (i) : mesh_->vertices[i]);
  }

  TileInput
  MemoryTileSource::loadTile (std::size_t t) const
  {
    if (t >= grid_.size ())
      throw Error ("MemoryTileSource: tile " + std::to_string (t) + " out of range (" + std::to_string (grid_.size ()) +
                   " tiles)");
    const Eigen::AlignedBox3d box = grid_.marginBox (t);
    TileInput input;
    if (scan_)
    {
      const ScanCloud& scan = *scan_;
      auto tile = std::make_shared<ScanCloud> ();
      tile->origin = scan.origin;
      tile->sensor_origin = scan.sensor_origin;
      tile->sensor_orientation = scan.sensor_orientation;
      tile->has_sensor_pose = sensor_pose_;
      tile->sensor_pose_checked = true;
      tile->stepped_axes = stepped_axes_;
      tile->fields = scan.fields;
      for (std::size_t i = 0; i < scan.size (); ++i)
        if (tile_of_[i] == t || inMargin (i, box))
        {
          tile->positions.push_back (scan.positions[i]);
          copyIfPresent (scan.normals, i, tile->normals);
          copyIfPresent (scan.colors, i, tile->colors);
          copyIfPresent (scan.intensities, i, tile->intensities);
          copyIfPresent (scan.viewpoints, i, tile->viewpoints);
          copyIfPresent (scan.indices, i, tile->indices);
          input.point_numbers.push_back (i);
        }
      tile->width = static_cast<std::uint32_t> (tile->size ());
      tile->height = 1;
      if (scan.isOrganized ())  // a camera frame's tile keeps the frame's image grid, as the untiled scan
        cropToPixelWindow (*tile, scan.width, scan.height);
      tile->report.input_points = tile->report.kept = tile->size ();
      // In the tile's own frame, as a spilled tile is (tile_source.h): the encoding depends on the frame
      // in its last bits, and the file must not depend on -memory (found by a review).
      centreScan (*tile);
      input.scan = tile;
      return input;
    }
    const TriangleMesh& mesh = *mesh_;
    auto tile = std::make_shared<TriangleMesh> ();
    std::vector<int> renumbered (mesh.vertices.size (), -1);
    for (const Eigen::Vector3i& f : mesh.triangles)
    {
      bool inside = false;
      for (int k = 0; k < 3 && !inside; ++k)
        inside = f[k] >= 0 && static_cast<std::size_t> (f[k]) < mesh.vertices.size () &&
                 (tile_of_[f[k]] == t || inMargin (f[k], box));
      if (!inside)
        continue;
      Eigen::Vector3i g;
      for (int k = 0; k < 3; ++k)
      {
        if (f[k] < 0 || static_cast<std::size_t> (f[k]) >= mesh.vertices.size ())
          throw Error ("MemoryTileSource: face index " + std::to_string (f[k]) + " out of range");
        int& r = renumbered[f[k]];
        if (r < 0)
        {
          r = static_cast<int> (tile->vertices.size ());
          tile->vertices.push_back (mesh.vertices[f[k]]);
          input.point_numbers.push_back (static_cast<std::size_t> (f[k]));
        }
        g[k] = r;
      }
      tile->triangles.push_back (g);
    }
    input.mesh = tile;
    return input;
  }
} // namespace pcl_sparse
