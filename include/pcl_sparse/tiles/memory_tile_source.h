#pragma once
/// \file memory_tile_source.h
/// The TileSource of an input held in memory (issue 16): tiles cut out of a loaded scan or mesh. The
/// file-backed source (for inputs larger than memory) gives the same tile inputs.

#include <pcl_sparse/io/scan_cloud.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/model/tile_grid.h>
#include <pcl_sparse/tiles/tile_source.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  /// \brief Tiles of a scan or mesh in memory. A scan tile keeps the points of the margin box in the scan's
  /// order and local frame (same origin, positions copied: world positions are exactly the scan's), as an
  /// unorganized scan; a mesh tile keeps the faces with a corner in the margin box, in file order, their
  /// vertices renumbered in order of first use. point_numbers give each tile point's index in the input.
  class MemoryTileSource : public TileSource
  {
  public:
    using Ptr = std::shared_ptr<MemoryTileSource>;

    /// \brief Tiles of a cleaned scan (loadScanCloud).
    /// \param[in] scan     the scan (kept points only; its positions are in its local frame)
    /// \param[in] options  how the grid is chosen (makeTileGrid over the scan's world bounding box)
    /// \throws pcl_sparse::Error for an empty scan or non-finite positions
    MemoryTileSource (const ScanCloud::ConstPtr& scan, const TileGridOptions& options);

    /// \brief Tiles of a mesh (loadTriangleMesh).
    /// \param[in] mesh     the mesh
    /// \param[in] options  how the grid is chosen (makeTileGrid over the vertices' bounding box)
    /// \throws pcl_sparse::Error for a mesh without vertices or with non-finite ones
    MemoryTileSource (const TriangleMesh::ConstPtr& mesh, const TileGridOptions& options);

    const TileGrid& grid () const override { return grid_; }
    std::size_t totalPoints () const override { return tile_of_.size (); }
    std::size_t corePoints (std::size_t t) const override { return core_counts_.at (t); }
    TileInput loadTile (std::size_t t) const override;

  private:
    /// Grid, tile of every point and core counts from the points' world positions.
    void cut (const std::vector<Eigen::Vector3d>& world, const TileGridOptions& options);
    /// Whether point \a i lies in tile \a t's margin box (closed).
    bool inMargin (std::size_t i, const Eigen::AlignedBox3d& box) const;

    ScanCloud::ConstPtr scan_;
    bool sensor_pose_ = false;  ///< the scan's pose orients its tiles (stated, and not PCL's default unsupported)
    std::uint8_t stepped_axes_ = 0;  ///< the scan's coordinates stored in steps (SteppedAxes), for its tiles
    TriangleMesh::ConstPtr mesh_;
    TileGrid grid_;
    std::vector<std::uint32_t> tile_of_;    ///< tile of each point (vertex)
    std::vector<std::size_t> core_counts_;  ///< points per tile core
  };
} // namespace pcl_sparse
