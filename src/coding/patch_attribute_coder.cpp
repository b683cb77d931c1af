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
                       const AttributeCodingInput& input)
  {
    std::vector<SparseCode> codes (input.channels.size ());
    if (positions.size () != patch.vertices.size () + extra_samples.size ())
      return codes;
    const std::vector<char> allowed = nyquistAllowedAtoms (*input.basis, spacing, input.nyquist_factor, input.nyquist_rule);
    std::vector<int> allowed_atoms;
    for (int k = 0; k < static_cast<int> (allowed.size ()); ++k)
      if (allowed[k])
        allowed_atoms.push_back (k);
    Eigen::MatrixXd dictionary;
    input.basis->evaluate (positions, allowed_atoms, dictionary);
    for (std::size_t c = 0; c < codes.size (); ++c)
    {
      const Eigen::VectorXd signal = channelSignal (patch, extra_samples, *input.values, static_cast<Eigen::Index> (c));
      const double norm = signal.norm ();
      if (!(norm > 0.0))
        continue;
      // OMP's tolerance is relative to ||y||: an RMS target t over P samples is ||r|| <= t sqrt(P).
      const double range = input.channels[c].upper - input.channels[c].lower;
      const double target = input.options.tolerance * range * std::sqrt (static_cast<double> (signal.size ()));
      const OmpResult omp = orthogonalMatchingPursuit (signal, dictionary, {}, target / norm, input.options.max_atoms);
      for (int a : omp.atoms)
        codes[c].atoms.push_back (allowed_atoms[a]);
      codes[c].coefficients = omp.coefficients;
    }
    return codes;
  }
} // namespace pcl_sparse
