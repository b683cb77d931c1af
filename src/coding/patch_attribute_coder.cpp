#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>
#include <pcl_sparse/coding/patch_attribute_coder.h>

#include <cmath>

namespace pcl_sparse
{
  namespace
  {
    /// Channel \a c at the samples: the vertices' values, then the extra points' interpolated ones.
    Eigen::VectorXd
    channelSignal (const Patch& patch, const std::vector<PatchSurfacePoint>& extra_samples, const VertexAttributes& values,
                   Eigen::Index c)
    {
      const auto column = values.values.col (c);
      const std::size_t n = patch.vertices.size ();
      Eigen::VectorXd signal (static_cast<Eigen::Index> (n + extra_samples.size ()));
      for (std::size_t i = 0; i < n; ++i)
        signal[static_cast<Eigen::Index> (i)] = column[patch.vertices[i]];
      for (std::size_t s = 0; s < extra_samples.size (); ++s)
      {
        const PatchSurfacePoint& point = extra_samples[s];
        double value = 0.0;
        for (int k = 0; k < 3; ++k)
          value += point.weights[k] * column[patch.vertices[point.corners[k]]];
        signal[static_cast<Eigen::Index> (n + s)] = value;
      }
      return signal;
    }
  } // namespace

  std::vector<SparseCode>
  codePatchAttributes (const Patch& patch, const std::vector<Eigen::Vector2d>& positions,
                       const std::vector<PatchSurfacePoint>& extra_samples, double spacing,
                       const AttributeCodingInput& input, const CodingDictionary* height_dictionary)
  {
    std::vector<SparseCode> codes (input.channels.size ());
    if (positions.size () != patch.vertices.size () + extra_samples.size () || codes.empty ())
      return codes;
    const std::vector<char> allowed = nyquistAllowedAtoms (*input.basis, spacing, input.nyquist_factor, input.nyquist_rule);
    std::vector<int> allowed_atoms;
    for (int k = 0; k < static_cast<int> (allowed.size ()); ++k)
      if (allowed[k])
        allowed_atoms.push_back (k);
    // The height's dictionary when it is the same matrix (same basis, samples and allowed atoms).
    Eigen::MatrixXd own_dictionary;
    const bool shared = height_dictionary && height_dictionary->basis == input.basis.get () &&
                        *height_dictionary->atoms == allowed_atoms &&
                        height_dictionary->matrix->rows () == static_cast<Eigen::Index> (positions.size ());
    if (!shared)
      input.basis->evaluate (positions, allowed_atoms, own_dictionary);
    const Eigen::MatrixXd& dictionary = shared ? *height_dictionary->matrix : own_dictionary;

    Eigen::MatrixXd signals (static_cast<Eigen::Index> (positions.size ()), static_cast<Eigen::Index> (codes.size ()));
    std::vector<double> tolerances (codes.size ());
    for (std::size_t c = 0; c < codes.size (); ++c)
    {
      signals.col (c) = channelSignal (patch, extra_samples, *input.values, static_cast<Eigen::Index> (c));
      // OMP's tolerance is relative to ||y||: an RMS target t over P samples is ||r|| <= t sqrt(P).
      const double norm = signals.col (c).norm ();
      const double range = input.channels[c].upper - input.channels[c].lower;
      const double target = input.options.tolerance * range * std::sqrt (static_cast<double> (signals.rows ()));
      tolerances[c] = norm > 0.0 ? target / norm : 0.0;
    }
    const std::vector<OmpResult> omp = batchOrthogonalMatchingPursuit (signals, dictionary, tolerances, input.options.max_atoms);
    for (std::size_t c = 0; c < codes.size (); ++c)
    {
      for (int a : omp[c].atoms)
        codes[c].atoms.push_back (allowed_atoms[a]);
      codes[c].coefficients = omp[c].coefficients;
    }
    return codes;
  }
} // namespace pcl_sparse
