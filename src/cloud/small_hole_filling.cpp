#include <pcl_sparse/cloud/small_hole_filling.h>

#include <Eigen/Geometry>

#include "edge_set.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>

namespace pcl_sparse
{
  namespace
  {
    /// Ears of the loop \a loop (vertex indices in hole order) appended to \a ears; false if it cannot be
    /// filled whole.
    bool
    earClip (std::vector<int> loop, const std::vector<Eigen::Vector3d>& positions,
             const std::vector<Eigen::Vector3d>& normals, const std::vector<double>& spacing, double gap_factor,
             const EdgeSet& used, std::vector<Eigen::Vector3i>& ears)
    {
      EdgeSet added (2 * loop.size ());
      while (loop.size () >= 3)
      {
        const std::size_t m = loop.size ();
        double best = std::numeric_limits<double>::infinity ();
        std::size_t chosen = m;
        for (std::size_t k = 0; k < m; ++k)
        {
          const int a = loop[k], b = loop[(k + 1) % m], c = loop[(k + 2) % m];
          const double length = (positions[c] - positions[a]).norm ();
          const Eigen::Vector3d area = (positions[b] - positions[a]).cross (positions[c] - positions[a]);
          if (m > 3 && (used.contains (a, c) || used.contains (c, a) || added.contains (a, c) ||
                        length > gap_factor * std::min (spacing[a], spacing[c])))
            continue;
          if (!(area.dot (normals[a] + normals[b] + normals[c]) > 0.0) || !(length < best))
            continue;
          best = length;
          chosen = k;
        }
        if (chosen == m)
          return false;
        const int a = loop[chosen], b = loop[(chosen + 1) % m], c = loop[(chosen + 2) % m];
        ears.emplace_back (a, b, c);
        added.insert (a, c);
        added.insert (c, a);
        loop.erase (loop.begin () + static_cast<std::ptrdiff_t> ((chosen + 1) % m));
        if (m == 3)
          break;
      }
      return true;
    }
  } // namespace

  std::size_t
  fillSmallHoles (const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
                  const std::vector<double>& spacing, double gap_factor, std::size_t max_edges,
                  std::vector<Eigen::Vector3i>& triangles)
  {
    EdgeSet used (3 * triangles.size ());
    for (const auto& t : triangles)
      for (int c = 0; c < 3; ++c)
        used.insert (t[c], t[(c + 1) % 3]);
    // Hole edges: the boundary edges reversed; next[b] = a for a boundary edge a -> b.
    std::map<int, std::vector<int>> next;
    for (const auto& t : triangles)
      for (int c = 0; c < 3; ++c)
      {
        const int a = t[c], b = t[(c + 1) % 3];
        if (!used.contains (b, a))
          next[b].push_back (a);
      }
    std::size_t filled = 0;
    std::vector<std::uint8_t> visited (positions.size (), 0);
    std::vector<int> loop;
    std::vector<Eigen::Vector3i> ears;
    for (const auto& [start, outgoing] : next)
    {
      if (outgoing.size () != 1 || visited[start])
        continue;
      loop.assign (1, start);
      bool simple = true;
      for (int v = outgoing[0]; v != start; )
      {
        const auto it = next.find (v);
        if (it == next.end () || it->second.size () != 1 || loop.size () >= max_edges || visited[v])
        {
          simple = false;
          break;
        }
        loop.push_back (v);
        v = it->second[0];
      }
      for (const int v : loop)
        visited[v] = 1;
      ears.clear ();
      if (!simple || loop.size () < 3 || !earClip (loop, positions, normals, spacing, gap_factor, used, ears))
        continue;
      for (const auto& t : ears)
      {
        triangles.push_back (t);
        for (int c = 0; c < 3; ++c)
          used.insert (t[c], t[(c + 1) % 3]);
      }
      ++filled;
    }
    return filled;
  }
} // namespace pcl_sparse
