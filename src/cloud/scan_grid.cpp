#include <pcl_sparse/cloud/scan_grid.h>

#include <pcl_sparse/common/error.h>

#include <string>

namespace pcl_sparse
{
  ScanGrid
  organizedScanGrid (const ScanCloud& scan, const std::vector<std::uint8_t>& placed)
  {
    const std::size_t n = scan.size ();
    if (!scan.indices.empty () && scan.indices.size () != n)
      throw Error ("buildCloudSurface: the scan has " + std::to_string (scan.indices.size ()) + " indices for " +
                   std::to_string (n) + " points");
    const std::size_t pixels = static_cast<std::size_t> (scan.width) * scan.height;
    // Without indices point i is pixel i, which only holds for a scan of every pixel: fewer points shifted
    // the rows, and the grid's triangles joined points of other pixels without a word.
    if (scan.indices.empty () && n != pixels)
      throw Error ("buildCloudSurface: the organized scan has " + std::to_string (n) + " points for its " +
                   std::to_string (scan.width) + " x " + std::to_string (scan.height) +
                   " pixels and no indices naming each point's pixel");
    ScanGrid grid;
    grid.width = static_cast<int> (scan.width);
    grid.height = static_cast<int> (scan.height);
    grid.cells.assign (pixels, -1);
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::size_t pixel = scan.indices.empty () ? i : scan.indices[i];
      if (pixel >= pixels)
        throw Error ("buildCloudSurface: point " + std::to_string (i) + " has pixel index " + std::to_string (pixel) +
                     ", outside the " + std::to_string (scan.width) + " x " + std::to_string (scan.height) + " grid");
      if (!placed[i])
        continue;
      if (grid.cells[pixel] >= 0)
        throw Error ("buildCloudSurface: points " + std::to_string (grid.cells[pixel]) + " and " + std::to_string (i) +
                     " have the same pixel index " + std::to_string (pixel));
      grid.cells[pixel] = static_cast<int> (i);
    }
    return grid;
  }
} // namespace pcl_sparse
