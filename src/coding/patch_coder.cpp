#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>
#include <pcl_sparse/coding/patch_attribute_coder.h>
#include <pcl_sparse/coding/patch_coder.h>
#include <pcl_sparse/coding/patch_footprint.h>
#include <pcl_sparse/coding/patch_samples.h>
#include <pcl_sparse/coding/radius_grid.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/geometry/quadric_fit.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pcl_sparse
{
  namespace
  {
    /// Heights (local units, fractions of r_P) whose RMS is below this are round-off of a flat patch, not
    /// shape: a relative tolerance alone spent up to L atoms fitting them (a tilted plane, the flat faces
    /// of a rotated CAD part). Double round-off in R^T (p - s) / r_P is about 1e-16.
    constexpr double kRoundOffHeight = 1e-12;

    /// Where the coefficients after the first \a k atoms start in PatchCodingInfo::prefix_coefficients
    /// (prefixes of 1, 2, ... atoms one after the other; k = 0 has none).
    std::size_t
    prefixOffset (std::size_t k)
    {
      return k > 0 ? k * (k - 1) / 2 : 0;
    }

    /// With the quadric basis, atoms whose RMS over a patch's samples is below this are not used (their
    /// coefficient would be 100 times the heights they fit), and an atom must bring this fraction of its
    /// squared norm outside the support's span (1 % of its norm): OmpSelection.
    constexpr double kMinQuadricColumnRms = 0.01;
    constexpr double kMinQuadricNewFraction = 1e-4;

    /// OMP's relative tolerance: eps, or looser where the noise level is reached first (a residual RMS of
    /// noise_level / r_P in local units, or the patch's own noise if larger), at most 1 (the empty code:
    /// the patch's plane).
    double
    stoppingTolerance (const Eigen::VectorXd& signal, const Patch& patch, const SparseCodingOptions& options)
    {
      const double norm = signal.norm ();
      if (norm > 0.0 && norm <= kRoundOffHeight * std::sqrt (static_cast<double> (signal.size ())))
        return 1.0;  // the empty code: the patch's plane
      if (!(options.noise_level > 0.0) || !(norm > 0.0) || !(patch.radius > 0.0))
        return options.tolerance;
      double noise = options.noise_level / patch.radius;
      if (options.local_noise)
        noise = std::max (noise, quadricNoiseLevel (patch.local));
      const double noise_norm = noise * std::sqrt (static_cast<double> (signal.size ()));
      return std::min (1.0, std::max (options.tolerance, noise_norm / norm));
    }
  } // namespace

  PatchCode
  codePatch (const Patch& input_patch, std::size_t patch_index, const TriangleMesh& mesh,
             const std::vector<double>& mean_ring_edge_lengths, const SurfaceBasis& basis, const SparseCodingOptions& options, PatchCodingInfo* info,
             const AttributeCodingInput* attributes, const MeshTopology* topology)
  {
    // A support scale s > 1 is the same patch with radius s r_P (local coordinates divided by s); the radius
    // on its grid is one more such scale.
    const double supported = input_patch.radius * (options.support_scale > 0.0 ? options.support_scale : 1.0);
    const double radius = options.radius_on_grid ? radiusOnGrid (supported) : supported;
    const double scale = radius / input_patch.radius;
    Patch scaled;
    const bool rescale = radius != input_patch.radius && scale > 0.0 && std::isfinite (scale);
    if (rescale)
    {
      scaled = input_patch;
      scaled.radius = radius;
      for (Eigen::Vector3d& p : scaled.local)
        p /= scale;
    }
    const Patch& patch = rescale ? scaled : input_patch;

    PatchCode code;
    code.origin = patch.origin;
    code.frame = patch.frame;
    code.radius = patch.radius;
    code.vertices = patch.vertices;
    code.vertex_xy.reserve (patch.local.size ());
    for (const Eigen::Vector3d& p : patch.local)
      code.vertex_xy.emplace_back (p.x (), p.y ());
    code.footprint = computePatchFootprint (patch, mesh, options.footprint_angles, options.clip_footprints_at_holes,
                                           options.clip_footprints_at_border && !patch.beside_uncovered_face,
                                           options.footprint_reach_degrees, topology,
                                           options.footprint_reach_max_tilt_degrees);

    // Samples: the vertices, then extra points on the patch's own triangles (docs/METHOD.md step 7).
    std::vector<Eigen::Vector2d> positions (code.vertex_xy);
    std::vector<double> heights;
    heights.reserve (patch.local.size ());
    for (const Eigen::Vector3d& p : patch.local)
      heights.push_back (p.z ());
    const int missing =
        std::max (options.min_samples - static_cast<int> (patch.local.size ()),
                  static_cast<int> (std::ceil (options.triangle_samples * static_cast<double> (patch.triangles.size ()))));
    const std::vector<PatchSurfacePoint> extra_samples =
        drawPatchSurfacePoints (patch, mesh, missing, mixSeed (options.seed, patch_index));
    for (const PatchSurfacePoint& sample : extra_samples)
    {
      const Eigen::Vector3d p = sample.interpolate (patch.local);
      positions.emplace_back (p.x (), p.y ());
      heights.push_back (p.z ());
    }

    const double spacing = patchSampleSpacing (patch, mean_ring_edge_lengths);
    const std::vector<char> allowed =
        nyquistAllowedAtoms (basis, spacing, options.nyquist_factor, options.nyquist_rule);

    // OMP over the allowed atoms only (the cap typically leaves a third of them): same result, less work.
    const std::vector<int> allowed_atoms = allowedAtomIndices (allowed);
    Eigen::MatrixXd dictionary;
    basis.evaluate (positions, allowed_atoms, dictionary);
    const Eigen::VectorXd signal = Eigen::Map<const Eigen::VectorXd> (heights.data (), heights.size ());
    // A quadric basis: its constant and monomials are preferred (SparseCodingOptions::quadric_preference).
    std::vector<char> preferred;
    const auto* cosine = dynamic_cast<const CosineAtoms*> (&basis);
    if (cosine && cosine->monomials () > 0)
    {
      preferred.assign (allowed_atoms.size (), 1);
      for (std::size_t k = 0; k < allowed_atoms.size (); ++k)
        if (allowed_atoms[k] == 0 || cosine->isMonomial (allowed_atoms[k]))
          preferred[k] = 2;
    }
    OmpSelection selection;
    if (!preferred.empty ())
    {
      // The quadric's atoms are nearly dependent on some cosines over small or thin sample sets: the
      // conditioning floors keep their coefficients from cancelling in the thousands (a scan's strip of
      // samples coded y with -4e4 without them).
      selection.preference = options.quadric_preference;
      selection.min_column_rms = kMinQuadricColumnRms;
      selection.min_new_fraction = kMinQuadricNewFraction;
      selection.orthogonal_scores = true;
    }
    OmpResult omp = orthogonalMatchingPursuit (signal, dictionary, preferred, stoppingTolerance (signal, patch, options),
                                               options.max_atoms, selection);
    code.atoms.reserve (omp.atoms.size ());
    for (int a : omp.atoms)
      code.atoms.push_back (allowed_atoms[a]);
    code.coefficients = std::move (omp.coefficients);
    if (attributes && attributes->values && attributes->basis && !attributes->channels.empty ())
    {
      const CodingDictionary height_dictionary{&basis, &allowed_atoms, &dictionary};
      code.attributes = codePatchAttributes (patch, positions, extra_samples, spacing, *attributes, &height_dictionary);
    }

    if (info)
    {
      info->num_samples = static_cast<int> (positions.size ());
      info->spacing = spacing;
      info->allowed_atoms = 0;
      for (char a : allowed)
        info->allowed_atoms += a != 0;
      const double norm = signal.norm ();
      info->relative_residual = norm > 0.0 ? omp.residual_norm / norm : 0.0;
      info->residual_norms = omp.residual_norms;
      info->prefix_coefficients = std::move (omp.prefix_coefficients);
    }
    return code;
  }

  void
  truncatePatchCode (int max_atoms, PatchCode& code, PatchCodingInfo& info)
  {
    const std::size_t k = static_cast<std::size_t> (std::max (max_atoms, 0));
    if (k >= code.atoms.size ())
      return;
    if (info.prefix_coefficients.size () < k * (k + 1) / 2 || info.residual_norms.size () <= k)
      throw Error ("truncatePatchCode: the coding info holds no prefix of " + std::to_string (k) + " atoms");
    code.atoms.resize (k);
    const auto first = info.prefix_coefficients.begin () + static_cast<std::ptrdiff_t> (prefixOffset (k));
    code.coefficients.assign (first, first + static_cast<std::ptrdiff_t> (k));
    info.residual_norms.resize (k + 1);
    info.prefix_coefficients.resize (k * (k + 1) / 2);
    const double norm = info.residual_norms.front ();
    info.relative_residual = norm > 0.0 ? info.residual_norms.back () / norm : 0.0;
  }

  int
  shortestPrefixWithin (const PatchCode& code, const SurfaceBasis& basis, const PatchCodingInfo& info,
                        double max_change)
  {
    const std::size_t n = code.atoms.size ();
    if (info.prefix_coefficients.size () < n * (n + 1) / 2)
      return static_cast<int> (n);
    const double half_width = code.boundHalfWidth ();
    std::vector<double> bounds (n);
    for (std::size_t i = 0; i < n; ++i)
      bounds[i] = basis.atomBound (code.atoms[i], half_width);
    for (std::size_t k = 0; k < n; ++k)
    {
      const double* prefix = info.prefix_coefficients.data () + prefixOffset (k);
      double change = 0.0;
      for (std::size_t i = 0; i < n; ++i)
        change += std::abs (code.coefficients[i] - (i < k ? prefix[i] : 0.0)) * bounds[i];
      if (change <= max_change)
        return static_cast<int> (k);
    }
    return static_cast<int> (n);
  }
} // namespace pcl_sparse
