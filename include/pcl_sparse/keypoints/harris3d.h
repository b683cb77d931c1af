#pragma once
/// \file harris3d.h
/// Harris 3D on triangle meshes (Sipiran & Bustos, The Visual Computer 2011; docs/METHOD.md step 3): the
/// per-vertex response and the keypoint selection, as plain functions. The PCL-style stage wrapping them
/// is HarrisKeypoint3DMesh (harris_keypoint3d_mesh.h).
///
/// Per vertex v: a ring neighbourhood; centred on its centroid; rotated by PCA so the smallest-eigenvalue
/// axis is z; translated so v is at the xy origin; least-squares fit of
///   z = p1/2 x^2 + p2 xy + p3/2 y^2 + p4 x + p5 y + p6;
/// E = [[A, C], [C, B]] with A = p4^2 + 2 p1^2 + 2 p2^2, B = p5^2 + 2 p2^2 + 2 p3^2,
/// C = p4 p5 + 2 p1 p2 + 2 p2 p3 (the Gaussian-integrated structure tensor of the fitted height);
/// R = det E - k (tr E)^2. R is invariant to rotations of the xy axes, so the PCA's axis signs and
/// in-plane order do not matter. It is not scale invariant (p1..p3 scale like 1 / length, p4, p5 not):
/// compare responses within one mesh, as the selection does.
///
/// Not to be confused with pcl::HarrisKeypoint3D (covariance of normals in a radius): a different
/// detector, compared in bench/results/harris.md.

#include <pcl_sparse/geometry/quadric_fit.h>
#include <pcl_sparse/mesh/mesh_topology.h>
#include <pcl_sparse/mesh/triangle_mesh.h>

#include <vector>

namespace pcl_sparse
{
  /// How keypoints are chosen among the 1-ring local maxima of the response.
  enum class Harris3DSelection
  {
    Fraction,   ///< the \a selection_fraction x #V local maxima with the largest response (paper default)
    Clustering  ///< greedy by decreasing response, dropping maxima closer than the cluster radius to a kept one
  };

  /// Options of Harris 3D. Defaults follow the paper (docs/METHOD.md step 3).
  struct Harris3DOptions
  {
    /// Harris constant k in R = det E - k (tr E)^2.
    double k = 0.04;
    /// Fixed number of rings when > 0 (the paper's option: 2); 0 selects the adaptive neighbourhood (default).
    int rings = 0;
    /// Adaptive neighbourhood: add rings until the neighbourhood radius exceeds this fraction of the
    /// bounding-box diagonal.
    double adaptive_fraction = 0.01;
    /// Adaptive neighbourhood: never more than this many rings.
    int max_rings = 16;
    /// A vertex whose neighbourhood has fewer neighbours (itself excluded) gets no response (NaN). The
    /// adaptive neighbourhood also keeps growing while it has fewer (within max_rings).
    int min_neighbors = 6;
    /// Keypoint selection rule.
    Harris3DSelection selection = Harris3DSelection::Fraction;
    /// Fraction selection: keep round(selection_fraction x #V) local maxima (at least 1), paper 0.01.
    double selection_fraction = 0.01;
    /// Clustering selection: minimum distance between keypoints as a fraction of the bounding-box diagonal.
    double cluster_fraction = 0.01;
    /// OpenMP threads for the responses; 0 = OpenMP's default. Results do not depend on it.
    int num_threads = 0;
  };

  /// Checks Harris 3D options.
  /// \param[in] options  the options
  /// \throws pcl_sparse::Error naming the first out-of-range field
  void
  validateHarris3DOptions (const Harris3DOptions& options);

  /// Harris response R = det E - k (tr E)^2 of a height quadric fitted in the PCA frame.
  /// \param[in] quadric  the fit; p1 .. p5 of docs/METHOD.md step 3 are c[3], c[4], c[5], c[1], c[2]
  /// \param[in] k        the Harris constant (0.04)
  /// \return R
  double
  harris3DResponseOfQuadric (const HeightQuadric& quadric, double k);

  /// Harris 3D response of every vertex. OpenMP over vertices; the result is the same for any thread
  /// count.
  /// \param[in] mesh      the mesh
  /// \param[in] topology  its topology
  /// \param[in] options   neighbourhood, Harris constant, threads
  /// \return #V responses; NaN where there is none (fewer than options.min_neighbors neighbours, a
  ///         degenerate fit, non-finite coordinates)
  std::vector<double>
  computeHarris3DResponses (const TriangleMesh& mesh, const MeshTopology& topology,
                            const Harris3DOptions& options = Harris3DOptions ());

  /// Harris 3D responses of some vertices only.
  /// \param[in] mesh      the mesh
  /// \param[in] topology  its topology
  /// \param[in] options   neighbourhood, Harris constant, threads
  /// \param[in] indices   the vertices to compute
  /// \return #V responses, NaN for the vertices not in \a indices
  std::vector<double>
  computeHarris3DResponses (const TriangleMesh& mesh, const MeshTopology& topology, const Harris3DOptions& options,
                            const std::vector<int>& indices);

  /// The strict total order of orderVerticesByResponse: whether \a a ranks before \a b (larger response,
  /// equal responses by increasing index, no finite response last). The seed sampling's candidate order.
  bool
  harris3DRanksBefore (const std::vector<double>& responses, int a, int b);

  /// Sorts \a vertices in the order of harris3DRanksBefore (the same order for any thread count).
  /// \param[in]     responses    #V responses (NaN: none)
  /// \param[in,out] vertices     vertex indices
  /// \param[in]     num_threads  OpenMP threads (0: all; at most two are used)
  void
  sortByHarris3DRank (const std::vector<double>& responses, std::vector<int>& vertices, int num_threads = 0);

  /// All vertex indices ordered by decreasing response: the candidate order of the feature-aware seed
  /// sampling (docs/METHOD.md step 4).
  /// \param[in] responses  #V responses (NaN: none)
  /// \return #V vertex indices; ties by increasing index, non-finite responses last (by index)
  std::vector<int>
  orderVerticesByResponse (const std::vector<double>& responses);

  /// Whether a vertex is a local maximum of the response over its 1-ring.
  /// \param[in] topology   the mesh's topology
  /// \param[in] responses  #V responses (NaN: none)
  /// \param[in] v          the vertex
  /// \return true if \a v has a finite response that beats every finite response of its 1-ring in the
  ///         order of orderVerticesByResponse (larger response, or equal response and smaller index)
  bool
  isHarris3DLocalMaximum (const MeshTopology& topology, const std::vector<double>& responses, int v);

  /// Keypoints from responses: 1-ring local maxima, then options.selection.
  /// \param[in] mesh            the mesh (for the clustering distance)
  /// \param[in] topology        its topology
  /// \param[in] responses       #V responses (NaN: none)
  /// \param[in] options         selection rule, fraction or cluster radius
  /// \param[in] num_candidates  the #V the selection fraction refers to (the number of vertices the
  ///                            responses were computed for)
  /// \return keypoint vertex indices in decreasing response (ties by index)
  std::vector<int>
  selectHarris3DKeypoints (const TriangleMesh& mesh, const MeshTopology& topology, const std::vector<double>& responses,
                           const Harris3DOptions& options, std::size_t num_candidates);
} // namespace pcl_sparse
