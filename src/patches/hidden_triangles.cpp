#include <pcl_sparse/patches/hidden_triangles.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

namespace pcl_sparse
{
  HiddenTriangleFinder::HiddenTriangleFinder (const TriangleMesh& mesh, const MeshTopology& topology,
                                              const PatchGrowthGeometry& geometry)
    : mesh_ (mesh), topology_ (topology), geometry_ (geometry), slot_ (mesh.triangles.size (), -1)
  {
  }

  std::vector<std::uint8_t>
  HiddenTriangleFinder::connectedToSeed (const Patch& patch)
  {
    const std::vector<int>& faces = patch.triangles;
    for (std::size_t i = 0; i < faces.size (); ++i)
      slot_[faces[i]] = static_cast<int> (i);
    std::vector<std::uint8_t> reached (faces.size (), 0);
    std::vector<int> stack;
    for (std::size_t i = 0; i < faces.size (); ++i)
    {
      const Eigen::Vector3i& t = mesh_.triangles[faces[i]];
      if (t[0] == patch.seed || t[1] == patch.seed || t[2] == patch.seed || faces[i] == patch.seed_face)
      {
        reached[i] = 1;
        stack.push_back (static_cast<int> (i));
      }
    }
    if (stack.empty () && !faces.empty ())  // no triangle at the seed: the first one stands for it
    {
      reached[0] = 1;
      stack.push_back (0);
    }
    while (!stack.empty ())
    {
      const int i = stack.back ();
      stack.pop_back ();
      for (int k = 0; k < 3; ++k)
      {
        const int g = topology_.face_neighbors[faces[i]][k];
        const int j = g >= 0 ? slot_[g] : -1;
        if (j >= 0 && !reached[j])
        {
          reached[j] = 1;
          stack.push_back (j);
        }
      }
    }
    for (int f : faces)
      slot_[f] = -1;
    return reached;
  }

  std::vector<int>
  HiddenTriangleFinder::find (const Patch& patch, double min_gap)
  {
    std::vector<int> hidden;
    const std::vector<std::uint8_t> connected = connectedToSeed (patch);
    if (std::all_of (connected.begin (), connected.end (), [] (std::uint8_t c) { return c != 0; }))
      return hidden;

    const Eigen::Vector3d& ns =
      patch.seed_face >= 0 ? geometry_.face_normals[patch.seed_face] : geometry_.vertex_normals[patch.seed];
    const Eigen::Vector3d e1 = ns.unitOrthogonal (), e2 = ns.cross (e1);
    const Eigen::Vector3d& s = mesh_.vertices[patch.seed];
    auto onPlane = [&] (int v) {
      const Eigen::Vector3d d = mesh_.vertices[v] - s;
      return Eigen::Vector2d (d.dot (e1), d.dot (e2));
    };
    double reach = 0.0;
    for (int f : patch.triangles)
      for (int k = 0; k < 3; ++k)
        reach = std::max (reach, onPlane (mesh_.triangles[f][k]).norm ());

    // What the segments may cross: the patch's triangles and the faces at its vertices on the seed's side.
    std::vector<int> cover (patch.triangles);
    for (int v : patch.vertices)
      for (int g : topology_.facesOf (v))
        if (geometry_.face_areas[g] > 0.0 && geometry_.face_normals[g].dot (ns) > 0.0)
          cover.push_back (g);
    std::sort (cover.begin (), cover.end ());
    cover.erase (std::unique (cover.begin (), cover.end ()), cover.end ());
    std::vector<std::array<Eigen::Vector2d, 3>> corners (cover.size ());
    for (std::size_t i = 0; i < cover.size (); ++i)
      for (int k = 0; k < 3; ++k)
        corners[i][k] = onPlane (mesh_.triangles[cover[i]][k]);

    std::vector<std::pair<double, double>> spans;
    for (std::size_t i = 0; i < patch.triangles.size (); ++i)
    {
      if (connected[i])
        continue;
      const Eigen::Vector3i& t = mesh_.triangles[patch.triangles[i]];
      const Eigen::Vector2d centroid = (onPlane (t[0]) + onPlane (t[1]) + onPlane (t[2])) / 3.0;
      const double length = centroid.norm ();
      if (!(length > 0.0))
        continue;
      const Eigen::Vector2d d = centroid / length;
      // The stretches [t0, t1] of the segment t d, 0 <= t <= length, inside each covering triangle.
      spans.clear ();
      for (const auto& q : corners)
      {
        const double orientation = (q[1] - q[0]).x () * (q[2] - q[0]).y () - (q[1] - q[0]).y () * (q[2] - q[0]).x ();
        if (orientation == 0.0)
          continue;
        double t0 = 0.0, t1 = length;
        for (int k = 0; k < 3 && t0 <= t1; ++k)
        {
          const Eigen::Vector2d edge = q[(k + 1) % 3] - q[k];
          const Eigen::Vector2d inward = orientation > 0.0 ? Eigen::Vector2d (-edge.y (), edge.x ())
                                                           : Eigen::Vector2d (edge.y (), -edge.x ());
          const double along = inward.dot (d), offset = inward.dot (q[k]);
          if (along > 0.0)
            t0 = std::max (t0, offset / along);
          else if (along < 0.0)
            t1 = std::min (t1, offset / along);
          else if (offset > 0.0)
            t1 = -1.0;
        }
        if (t0 <= t1)
          spans.emplace_back (t0, t1);
      }
      std::sort (spans.begin (), spans.end ());
      double covered_to = 0.0, gap = 0.0;
      for (const auto& [t0, t1] : spans)
      {
        gap += std::max (0.0, t0 - covered_to);
        covered_to = std::max (covered_to, t1);
      }
      gap += std::max (0.0, length - covered_to);
      if (gap > min_gap * reach)
        hidden.push_back (patch.triangles[i]);
    }
    return hidden;
  }

  std::vector<int>
  hiddenPatchTriangles (const TriangleMesh& mesh, const MeshTopology& topology, const PatchGrowthGeometry& geometry,
                        const Patch& patch, double min_gap)
  {
    return HiddenTriangleFinder (mesh, topology, geometry).find (patch, min_gap);
  }

  void
  removePatchTriangles (const TriangleMesh& mesh, const std::vector<int>& faces, Patch& patch)
  {
    auto removed = [&] (int f) { return std::find (faces.begin (), faces.end (), f) != faces.end (); };
    const std::size_t grown = patch.triangles.size () - std::min (patch.triangles.size (), patch.completed_triangles);
    std::vector<int> kept;
    std::size_t kept_completed = 0;
    std::vector<int> orphans;  // corners of the removed faces
    for (std::size_t i = 0; i < patch.triangles.size (); ++i)
    {
      const int f = patch.triangles[i];
      if (removed (f))
      {
        for (int k = 0; k < 3; ++k)
          orphans.push_back (mesh.triangles[f][k]);
        continue;
      }
      kept.push_back (f);
      kept_completed += i >= grown;
    }
    patch.triangles = std::move (kept);
    patch.completed_triangles = kept_completed;
    for (int f : patch.triangles)
      for (int k = 0; k < 3; ++k)
        orphans.erase (std::remove (orphans.begin (), orphans.end (), mesh.triangles[f][k]), orphans.end ());
    orphans.erase (std::remove (orphans.begin (), orphans.end (), patch.seed), orphans.end ());
    patch.vertices.erase (std::remove_if (patch.vertices.begin (), patch.vertices.end (),
                                          [&] (int v) { return std::find (orphans.begin (), orphans.end (), v) != orphans.end (); }),
                          patch.vertices.end ());
  }
} // namespace pcl_sparse
