#pragma once
/// \file test_format_models.h
/// Synthetic sparse models for the file-format tests and the fuzzer's seed corpus: random patches with
/// orthonormal frames (some reflected), log-uniform radii, star-shaped footprints and random sparse
/// codes over the 144-atom cosine dictionary. Seeded, so every run builds the same models.

#include <pcl_sparse/coding/cosine_dictionary.h>
#include <pcl_sparse/model/sparse_surface_model.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace pcl_sparse
{
  namespace test
  {
    inline SparseSurfaceModel
    makeSyntheticModel (std::size_t num_patches, unsigned seed, bool with_vertices = false, int footprint_angles = 16)
    {
      std::mt19937 rng (seed);
      std::uniform_real_distribution<double> uniform (0.0, 1.0);
      std::normal_distribution<double> normal (0.0, 1.0);
      SparseSurfaceModel model;
      auto basis = std::make_shared<CosineDictionary> (12);
      model.basis = basis;
      model.num_input_vertices = 1000;
      model.bbox_diagonal = 10.0 * std::sqrt (3.0);
      for (std::size_t p = 0; p < num_patches; ++p)
      {
        PatchCode patch;
        patch.origin = Eigen::Vector3d (10 * uniform (rng), 10 * uniform (rng), 10 * uniform (rng));
        Eigen::Quaterniond q (normal (rng), normal (rng), normal (rng), normal (rng));
        q.normalize ();
        patch.frame = q.toRotationMatrix ();
        if (p % 3 == 1)
          patch.frame.col (1) = -patch.frame.col (1);  // left-handed (T1, T2, N) occurs in practice
        patch.radius = 0.1 * std::exp (std::log (10.0) * uniform (rng));
        for (int k = 0; k < footprint_angles; ++k)
          patch.footprint.extent.push_back (static_cast<float> (0.4 + 0.6 * uniform (rng)));
        std::vector<int> atoms (basis->size ());
        std::iota (atoms.begin (), atoms.end (), 0);
        std::shuffle (atoms.begin (), atoms.end (), rng);
        const int n = 1 + static_cast<int> (p % 12);
        atoms.resize (n);
        if (p % 2 == 0)
          atoms[0] = 0;  // the constant atom first, as OMP usually picks it
        atoms.erase (std::remove (atoms.begin () + 1, atoms.end (), 0), atoms.end ());
        patch.atoms = atoms;
        for (std::size_t k = 0; k < patch.atoms.size (); ++k)
          patch.coefficients.push_back (0.3 * normal (rng) / (1.0 + k));
        if (with_vertices)
          for (int v = 0; v < 20; ++v)
          {
            patch.vertices.push_back (static_cast<int> (uniform (rng) * 999.0));
            patch.vertex_xy.emplace_back (2 * uniform (rng) - 1, 2 * uniform (rng) - 1);
          }
        model.patches.push_back (patch);
      }
      return model;
    }

    /// Adds colour and intensity to \a model: channels r, g, b (0 .. 255) and intensity (-50 .. 1000), one
    /// random sparse code per channel and patch over the half-period cosines, or another basis \a kind (some
    /// codes empty).
    inline void
    addSyntheticAttributes (SparseSurfaceModel& model, unsigned seed, CosineBasisKind kind = CosineBasisKind::Dct)
    {
      std::mt19937 rng (seed);
      std::normal_distribution<double> normal (0.0, 1.0);
      auto basis = makeCosineBasis (kind, 12);
      model.attribute_basis = basis;
      model.attribute_channels = {{AttributeChannel::Red, 0.0, 255.0}, {AttributeChannel::Green, 0.0, 255.0},
                                  {AttributeChannel::Blue, 0.0, 255.0}, {AttributeChannel::Intensity, -50.0, 1000.0}};
      for (std::size_t p = 0; p < model.patches.size (); ++p)
      {
        PatchCode& patch = model.patches[p];
        patch.attributes.assign (model.attribute_channels.size (), SparseCode ());
        for (std::size_t c = 0; c < patch.attributes.size (); ++c)
        {
          std::vector<int> atoms (basis->size ());
          std::iota (atoms.begin (), atoms.end (), 0);
          std::shuffle (atoms.begin (), atoms.end (), rng);
          atoms.resize ((p + 3 * c) % 9);  // 0 .. 8 atoms
          if (!atoms.empty ())
            atoms[0] = 0;  // the constant first: the channel's mean
          std::sort (atoms.begin () + (atoms.empty () ? 0 : 1), atoms.end ());
          atoms.erase (std::unique (atoms.begin (), atoms.end ()), atoms.end ());
          const double scale = c == 3 ? 300.0 : 40.0;
          for (std::size_t k = 0; k < atoms.size (); ++k)
          {
            patch.attributes[c].atoms.push_back (atoms[k]);
            patch.attributes[c].coefficients.push_back (k == 0 ? 3.0 * scale : scale * normal (rng) / (1.0 + k));
          }
        }
      }
    }

    /// The largest distance between the footprint \a decoded draws (linear between its angles) and
    /// \a original's extents, at \a original's angles.
    inline double
    largestFootprintDeviation (const PatchFootprint& original, const PatchFootprint& decoded)
    {
      double worst = 0.0;
      const std::size_t k = original.extent.size ();
      for (std::size_t i = 0; i < k; ++i)
        worst = std::max (worst, std::abs (decoded.extentAt (2.0 * M_PI * i / k) - original.extent[i]));
      return worst;
    }
  } // namespace test
} // namespace pcl_sparse
