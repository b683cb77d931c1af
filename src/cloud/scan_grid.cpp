#include <pcl_sparse/cloud/scan_grid.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
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

  void
  cropToPixelWindow (ScanCloud& part, std::uint32_t width, std::uint32_t height)
  {
    const std::size_t n = part.size ();
    if (part.indices.size () != n)
      throw Error ("cropToPixelWindow: " + std::to_string (part.indices.size ()) + " indices for " + std::to_string (n) +
                   " points");
    const std::size_t pixels = static_cast<std::size_t> (width) * height;
    std::size_t row0 = height, row1 = 0, column0 = width, column1 = 0;
    for (const std::size_t pixel : part.indices)
    {
      if (pixel >= pixels)
        throw Error ("cropToPixelWindow: pixel index " + std::to_string (pixel) + " is outside the " +
                     std::to_string (width) + " x " + std::to_string (height) + " image");
      row0 = std::min (row0, pixel / width);
      row1 = std::max (row1, pixel / width);
      column0 = std::min (column0, pixel % width);
      column1 = std::max (column1, pixel % width);
    }
    if (n == 0)
      row0 = row1 = column0 = column1 = 0;
    if (row1 == row0 && height > 1)  // a second row, empty, keeps the part organized
    {
      if (row1 + 1 < height)
        ++row1;
      else
        --row0;
    }
    const std::size_t window_width = column1 - column0 + 1;
    for (std::size_t& pixel : part.indices)
      pixel = (pixel / width - row0) * window_width + (pixel % width - column0);
    part.width = static_cast<std::uint32_t> (window_width);
    part.height = static_cast<std::uint32_t> (row1 - row0 + 1);
  }
} // namespace pcl_sparse
