#pragma once
/// \file patch_attribute_coder.h
/// Codes a patch's colour and intensity (ours; the paper codes geometry only). Each channel is a signal
/// over the patch's domain like the height, so it is coded the same way: OMP at the height's samples,
/// over the atoms of the attribute basis that pass the same Nyquist cap (the cap holds for any signal
/// sampled at the mesh's spacing). The height's code is computed first and never depends on them.
///
/// The attribute basis is the half-period cosines (CosineBasisKind::Dct) by default, whatever the
/// height's: the paper's atoms are all even in x and y, so they cannot code a colour gradient across a
/// patch at all (a ramp r = 128 + 100 x on the unit sphere, 172 patches: mean error 6.6 grey levels,
/// largest 53, against 0.55 and 3.3 with the half-period atoms; the height does not need the odd part
/// because its frame removes the tilt).

#include <pcl_sparse/coding/cosine_atoms.h>
#include <pcl_sparse/coding/nyquist_cap.h>
#include <pcl_sparse/coding/patch_samples.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/model/surface_basis.h>
#include <pcl_sparse/model/vertex_attributes.h>
#include <pcl_sparse/patches/patch.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_sparse
{
  /// Options of the attribute coding.
  struct AttributeCodingOptions
  {
    /// Atoms of the attribute codes (n^2 of them, n as the height's basis). Dct: both parities (default);
    /// Paper: the paper's even atoms, which cannot code gradients (see the file's comment).
    CosineBasisKind basis = CosineBasisKind::Dct;
    int max_atoms = 12;              ///< L, atoms per channel and patch at most
    /// OMP stops once the residual RMS over the patch's samples is at most this fraction of the channel's
    /// range (AttributeChannelInfo: 255 for colour, so the default is 1 grey level).
    double tolerance = 1.0 / 255.0;
  };

  /// The attributes codePatch codes along with the height (patch_coder.h).
  struct AttributeCodingInput
  {
    const VertexAttributes* values = nullptr;    ///< one row per vertex of the mesh the patches are on
    std::vector<AttributeChannelInfo> channels;  ///< values->channelInfo (faces): the ranges the tolerance refers to
    SurfaceBasis::ConstPtr basis;                ///< the attribute basis (SparseSurfaceModel::attribute_basis)
    double nyquist_factor = 0.5;                 ///< f of the height's coding (SparseCodingOptions)
    NyquistRule nyquist_rule = NyquistRule::Paper;
    AttributeCodingOptions options;
  };

  /// The dictionary matrix the height was coded over. The attributes reuse its first columns when they are
  /// the attribute atoms at the same samples: the same basis, or the quadric's cosines for the cosines alone.
  struct CodingDictionary
  {
    const SurfaceBasis* basis = nullptr;     ///< the basis evaluated
    const std::vector<int>* atoms = nullptr; ///< the atoms evaluated (the columns), ascending
    const Eigen::MatrixXd* matrix = nullptr; ///< the atoms at the samples: #samples by atoms->size ()
  };

  /// \brief One sparse code per attribute channel of \a patch.
  /// The samples are the patch's vertices (their attribute values), then \a extra_samples, points on the
  /// patch's triangles with the barycentric interpolation of their corners' values: what a renderer shows
  /// between the vertices, and what keeps a patch with fewer vertices than atoms from oscillating.
  /// \param[in] patch the patch (vertices: rows of input.values)
  /// \param[in] positions local (x, y) of the samples: the vertices, then the extra samples
  /// \param[in] extra_samples the extra points the height was coded at
  /// \param[in] spacing the patch's sample spacing mu (local units), for the Nyquist cap
  /// \param[in] input the attributes, their ranges, basis and options
  /// \param[in] height_dictionary the height's dictionary at the same samples, used if it is the same
  ///            matrix (the attribute basis is the height's, the same atoms allowed), else evaluated again
  /// \return input.channels.size () codes over input.basis
  std::vector<SparseCode>
  codePatchAttributes (const Patch& patch, const std::vector<Eigen::Vector2d>& positions,
                       const std::vector<PatchSurfacePoint>& extra_samples, double spacing,
                       const AttributeCodingInput& input, const CodingDictionary* height_dictionary = nullptr);
} // namespace pcl_sparse
