#include <pcl_sparse/mesh/vertex_welding.h>

#include <cstdint>
#include <cstring>

namespace pcl_sparse
{
  namespace
  {
    std::size_t
    positionHash (const Eigen::Vector3d& position)
    {
      std::uint64_t h = 0x9e3779b97f4a7c15ull;
      for (int k = 0; k < 3; ++k)
      {
        const double value = position[k] == 0.0 ? 0.0 : position[k];  // -0 hashes like +0
        std::uint64_t bits;
        std::memcpy (&bits, &value, sizeof (double));
        h = (h ^ bits) * 0xff51afd7ed558ccdull;
        h ^= h >> 32;
      }
      return static_cast<std::size_t> (h);
    }
  } // namespace

  FirstPositionTable::FirstPositionTable (const std::vector<Eigen::Vector3d>& points, std::size_t expected)
    : points_ (points)
  {
    std::size_t capacity = 64;
    while (capacity < 2 * expected)
      capacity *= 2;
    slots_.assign (capacity, -1);
  }

  std::size_t
  FirstPositionTable::add (const Eigen::Vector3d& position, std::size_t i)
  {
    if (2 * (count_ + 1) > slots_.size ())
      grow ();
    const std::size_t mask = slots_.size () - 1;
    for (std::size_t slot = positionHash (position) & mask;; slot = (slot + 1) & mask)
    {
      const int index = slots_[slot];
      if (index < 0)
      {
        slots_[slot] = static_cast<int> (i);
        ++count_;
        return i;
      }
      if (points_[static_cast<std::size_t> (index)] == position)
        return static_cast<std::size_t> (index);
    }
  }

  void
  FirstPositionTable::grow ()
  {
    std::vector<int> old;
    old.swap (slots_);
    slots_.assign (old.size () * 2, -1);
    const std::size_t mask = slots_.size () - 1;
    for (int index : old)
      if (index >= 0)
      {
        std::size_t slot = positionHash (points_[static_cast<std::size_t> (index)]) & mask;
        while (slots_[slot] >= 0)
          slot = (slot + 1) & mask;
        slots_[slot] = index;
      }
  }

  // Closed meshes have about corners / 6 distinct vertices.
  VertexWelder::VertexWelder (std::vector<Eigen::Vector3d>& vertices, std::size_t expected_corners)
    : vertices_ (vertices), first_ (vertices, expected_corners / 6)
  {
    vertices_.clear ();
  }

  int
  VertexWelder::add (const Eigen::Vector3d& position)
  {
    const std::size_t first = first_.add (position, vertices_.size ());
    if (first == vertices_.size ())
      vertices_.push_back (position);
    return static_cast<int> (first);
  }

  std::vector<int>
  findCoincidentVertices (const TriangleMesh& mesh)
  {
    std::vector<Eigen::Vector3d> distinct;
    std::vector<int> first_of_distinct, first (mesh.vertices.size ());
    VertexWelder welder (distinct, 3 * mesh.vertices.size ());
    for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
    {
      const std::size_t d = static_cast<std::size_t> (welder.add (mesh.vertices[v]));
      if (d == first_of_distinct.size ())
        first_of_distinct.push_back (static_cast<int> (v));
      first[v] = first_of_distinct[d];
    }
    return first;
  }

  bool
  isTriangleSoup (const TriangleMesh& mesh)
  {
    if (mesh.triangles.size () < 2)
      return false;
    std::vector<int> face_of (mesh.vertices.size (), -1);
    for (std::size_t f = 0; f < mesh.triangles.size (); ++f)
      for (int k = 0; k < 3; ++k)
      {
        const std::size_t v = static_cast<std::size_t> (mesh.triangles[f][k]);
        if (v >= face_of.size ())
          return false;  // not a valid mesh: nothing to say about its topology
        if (face_of[v] >= 0 && face_of[v] != static_cast<int> (f))
          return false;
        face_of[v] = static_cast<int> (f);
      }
    return true;
  }
} // namespace pcl_sparse
