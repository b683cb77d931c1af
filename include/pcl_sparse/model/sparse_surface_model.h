#pragma once
/// \file sparse_surface_model.h
/// The sparse-code surface model: overlapping height-field patches coded over a SurfaceBasis
/// (docs/METHOD.md steps 9-12). It is what the encoder produces, what resampling reads, and what the file
/// format stores.

#include <pcl_sparse/model/surface_basis.h>
#include <pcl_sparse/model/vertex_attributes.h>

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace pcl_sparse
{
  /// Where a patch has data in its own tangent plane: a star-shaped region around the seed given by its
  /// radial extent at K equally spaced angles (angle 2 pi k / K, measured from T1 towards T2), in local
  /// scaled units (the unit disk holds every patch vertex). Between angles the extent is interpolated
  /// linearly. Patches grow by geodesic distance from the seed, so they are star-shaped in practice.
  struct PatchFootprint
  {
    std::vector<float> extent;  ///< K radii in [0, ~1]
    /// One per angle, 1 where trimFlippedPlaces drew the extent in because the code's normal points away
    /// from the input surface just past it (resampling/flipped_places.h): a quantised file draws the border
    /// there no further out (format/footprint_coding.h). Empty: no angle was cut. Files do not store it.
    std::vector<char> trimmed;

    /// Extent at \a angle (radians), linearly interpolated.
    double extentAt (double angle) const;
    /// Whether (x, y) lies inside the footprint.
    bool contains (double x, double y) const;
    /// The largest extent (0 without extents): every point of the footprint lies within it of the seed.
    double largestExtent () const;
  };

  /// A sparse code over a model's basis: sum_k coefficients[k] * atom_{atoms[k]}.
  struct SparseCode
  {
    std::vector<int> atoms;            ///< atom indices, in selection order
    std::vector<double> coefficients;  ///< one per atom
  };

  /// One coded patch.
  struct PatchCode
  {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero ();     ///< s, world position of the seed
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity ();  ///< R = (T1, T2, N) as columns
    double radius = 1.0;                                   ///< r_P, world units per local unit
    std::vector<int> atoms;                                ///< selected atom indices, in selection order
    std::vector<double> coefficients;                      ///< one per atom, for the atoms as defined
    PatchFootprint footprint;

    /// Input vertices this patch covers and their local (x', y'): needed only to reconstruct the input
    /// vertices (docs/METHOD.md step 10); empty in a model loaded without its mesh.
    std::vector<int> vertices;
    std::vector<Eigen::Vector2d> vertex_xy;

    /// One code per attribute channel of the model (SparseSurfaceModel::attribute_channels), over the same
    /// basis and local (x, y) as the height; empty when the model has no attributes.
    std::vector<SparseCode> attributes;

    Eigen::Vector3d toWorld (const Eigen::Vector3d& local) const { return origin + radius * (frame * local); }
    /// Local point R^T (p - s) / r_P of the world point \a p, as Patch::toLocal (r_P includes the support scale).
    Eigen::Vector3d toLocal (const Eigen::Vector3d& p) const { return frame.transpose () * (p - origin) / radius; }
    /// Bound on the code's |h| (local units) over the patch square [-1, 1]^2 and its footprint: the sum of
    /// its coefficients' magnitudes, each times its atom's bound (SurfaceBasis::atomBound) over the square
    /// |x|, |y| <= max (1, largest extent). Not just the sum: the quadric's x^2 reaches e^2 > 1 where a
    /// footprint reaches e > 1 (merged patches).
    /// \param[in] basis the basis the code is over (SparseSurfaceModel::basis)
    double heightBound (const SurfaceBasis& basis) const;
    /// max (1, largest footprint extent): the half-width of the square around the seed that holds the patch
    /// square and its footprint, over which heightBound bounds the atoms.
    double boundHalfWidth () const;
  };

  /// Figures of a model against its input mesh (docs/METHOD.md step 11).
  struct ModelStatistics
  {
    std::size_t num_vertices = 0;      ///< N_V, input vertices
    std::size_t num_patches = 0;       ///< M
    std::size_t num_nonzeros = 0;      ///< ||alpha||_0
    std::size_t uncovered = 0;         ///< input vertices in no patch (left out of the errors)
    double rmse = 0.0;                 ///< sqrt(mean |v - v^|^2) over covered vertices
    double rmse_over_diagonal = 0.0;   ///< rmse / bounding-box diagonal of the input
    double max_error = 0.0;            ///< largest |v - v^|
    double mean_error_over_diagonal = 0.0;  ///< mean |v - v^| over covered vertices / bbox diagonal
    double compression_ratio = 0.0;    ///< CR = (13 M + nnz) / (3 N_V)
  };

  /// The whole model.
  /// CR = (13 M + nnz) / (3 N_V) (docs/METHOD.md step 11); 0 when \a num_vertices is 0.
  double
  compressionRatio (std::size_t num_patches, std::size_t num_nonzeros, std::size_t num_vertices);

  class SparseSurfaceModel
  {
  public:
    using Ptr = std::shared_ptr<SparseSurfaceModel>;
    using ConstPtr = std::shared_ptr<const SparseSurfaceModel>;

    SurfaceBasis::ConstPtr basis;    ///< the dictionary every patch is coded over
    std::vector<PatchCode> patches;
    std::size_t num_input_vertices = 0;
    double bbox_diagonal = 0.0;      ///< of the input mesh
    /// How far inside its true extent a footprint may be drawn at a knife edge, in local units: 0 for an
    /// encoded or lossless model, one extent level for a quantised file's (its writer keeps the border there
    /// within a level, format/footprint_coding.h). Resampling clears the other side's places that much past
    /// the border (PatchOwnership).
    double footprint_step = 0.0;
    /// Colour / intensity channels every patch codes (PatchCode::attributes); empty: geometry only.
    std::vector<AttributeChannelInfo> attribute_channels;
    /// The basis the attribute codes are over (the encoder's default: half-period cosines, both parities,
    /// since colour gradients are odd; patch_attribute_coder.h). Set when attribute_channels is not empty.
    SurfaceBasis::ConstPtr attribute_basis;

    std::size_t numPatches () const { return patches.size (); }
    /// Total number of non-zero coefficients ||alpha||_0.
    std::size_t numNonZeros () const;
    /// Height, gradient and Hessian of patch \a p at local (x, y).
    HeightSample evaluate (std::size_t p, double x, double y) const;

    /// Whether the patches code attribute channels.
    bool hasAttributes () const { return !attribute_channels.empty (); }
    /// Index of \a channel in attribute_channels, -1 if the model does not have it.
    int attributeIndex (AttributeChannel channel) const;
    /// Attribute channel \a c (index into attribute_channels) of patch \a p at local (x, y), clamped to the
    /// channel's range. 0 clamped to the range for a patch without that code.
    double evaluateAttribute (std::size_t p, std::size_t c, double x, double y) const;

    /// \brief Moves the whole model by \a offset (every patch's seed; frames, radii and codes are
    /// unchanged): the same surface in a frame whose origin is at -offset.
    /// \param[in] offset world translation
    void translate (const Eigen::Vector3d& offset);

    /// \brief Checks that every patch is a surface the model can evaluate: finite seed, orthonormal frame,
    /// finite positive radius, as many coefficients (finite) as atoms, atoms distinct and in the basis,
    /// footprint extents finite and >= 0; and the attribute codes (checkAttributeCodes). The file writer and
    /// resampling call it on models built in memory.
    /// \param[in] who  the start of the error message (e.g. "encodeModel: ")
    /// \throws pcl_sparse::Error naming the first patch and field that is not
    void checkPatches (const std::string& who) const;

    /// \brief Checks the attribute codes: none without attribute channels; else an attribute basis, known
    /// and distinct channels with finite ranges (lower <= upper), and per patch one code per channel with
    /// as many finite coefficients as atoms, atoms distinct and in the attribute basis (an atom outside it
    /// was read past the evaluator's tables when resampling).
    /// \param[in] who  the start of the error message
    /// \throws pcl_sparse::Error naming the first patch and field that is not
    void checkAttributeCodes (const std::string& who) const;

    /// CR = (13 M + nnz) / (3 N_V) (docs/METHOD.md step 11: 9 frame + 3 seed + 1 radius values per patch; counts
    /// values, not bytes). 0 when num_input_vertices is 0.
    double compressionRatio () const;

    /// Blended input vertices (docs/METHOD.md step 10): vertex v is the mean over the patches listing it of
    /// s + r R (x', y', h(x', y')), with its stored x', y'. Vertices in no patch (and indices >=
    /// \a num_vertices are ignored) come back as NaN. Needs the patches' vertices / vertex_xy.
    std::vector<Eigen::Vector3d> reconstructVertices (std::size_t num_vertices) const;

    /// Attributes of the input vertices, blended as reconstructVertices blends positions (mean over the
    /// patches listing a vertex of each channel's code at its x', y', clamped): \a num_vertices by
    /// attribute_channels.size(), NaN rows for vertices in no patch. Needs the patches' vertices / vertex_xy.
    Eigen::MatrixXf reconstructVertexAttributes (std::size_t num_vertices) const;

    /// Statistics against the input vertices; \a errors (optional) receives |v - v^| per vertex (0 for
    /// uncovered ones).
    ModelStatistics statistics (const std::vector<Eigen::Vector3d>& input_vertices,
                                std::vector<double>* errors = nullptr) const;
  };
} // namespace pcl_sparse
