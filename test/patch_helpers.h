#pragma once
// Hand-made patches for the tests of the stages that work on a partition (redundant patches, merging).

#include <pcl_sparse/patches/patch.h>

#include <utility>
#include <vector>

namespace pcl_sparse_test
{
  /// A patch seeded at its first vertex holding \a vertices and \a triangles, grown from \a seed_face.
  inline pcl_sparse::Patch
  makePatch (std::vector<int> vertices, std::vector<int> triangles, int seed_face = -1)
  {
    pcl_sparse::Patch patch;
    patch.seed = vertices.front ();
    patch.seed_face = seed_face;
    patch.vertices = std::move (vertices);
    patch.triangles = std::move (triangles);
    return patch;
  }
} // namespace pcl_sparse_test
