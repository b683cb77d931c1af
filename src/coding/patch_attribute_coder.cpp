#include <pcl_sparse/coding/patch_attribute_coder.h>

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/cosine_gram.h>
#include <pcl_sparse/coding/orthogonal_matching_pursuit.h>

#include <algorithm>
#include <cmath>
#include <optional>

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

    /// Whether atom k of \a height is atom k of \a attribute wherever \a attribute has one.
    bool
    sharesAtoms (const SurfaceBasis& height, const SurfaceBasis& attribute)
    {
      if (&height == &attribute)
        return true;
      const auto* height_cosines = dynamic_cast<const CosineAtoms*> (&height);
      const auto* attribute_cosines = dynamic_cast<const CosineAtoms*> (&attribute);
      return height_cosines && attribute_cosines && attribute_cosines->monomials () == 0 &&
             height_cosines->sameCosines (*attribute_cosines);
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
    const std::vector<int> allowed_atoms = allowedAtomIndices (allowed);
    // The height's dictionary's first columns when they are these atoms at these samples: the same basis,
    // or the quadric's cosines for the cosines alone (the default bases: that saved 2 % of a colour scan's
    // encoding CPU).
    Eigen::MatrixXd own_dictionary;
    const bool shared = height_dictionary && sharesAtoms (*height_dictionary->basis, *input.basis) &&
                        height_dictionary->atoms->size () >= allowed_atoms.size () &&
                        std::equal (allowed_atoms.begin (), allowed_atoms.end (), height_dictionary->atoms->begin ()) &&
                        height_dictionary->matrix->rows () == static_cast<Eigen::Index> (positions.size ());
    if (!shared)
      input.basis->evaluate (positions, allowed_atoms, own_dictionary);
    const Eigen::MatrixXd& columns = shared ? *height_dictionary->matrix : own_dictionary;
    const Eigen::Ref<const Eigen::MatrixXd> dictionary =
      columns.leftCols (static_cast<Eigen::Index> (allowed_atoms.size ()));

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
    // Cosine atoms' Gram columns from sums over the samples (CosineGram): O(K) each instead of O(#P K).
    GramColumnFunction gram_column;
    std::optional<CosineGram> gram;
    if (const auto* cosines = dynamic_cast<const CosineAtoms*> (input.basis.get ()); cosines && cosines->monomials () == 0)
    {
      gram.emplace (*cosines, positions, allowed_atoms);
      gram_column = [&gram] (int j, Eigen::Ref<Eigen::VectorXd> column) { gram->column (j, column); };
    }
    const std::vector<OmpResult> omp =
      batchOrthogonalMatchingPursuit (signals, dictionary, tolerances, input.options.max_atoms, gram_column);
    for (std::size_t c = 0; c < codes.size (); ++c)
    {
      for (int a : omp[c].atoms)
        codes[c].atoms.push_back (allowed_atoms[a]);
      codes[c].coefficients = omp[c].coefficients;
    }
    return codes;
  }
} // namespace pcl_sparse
