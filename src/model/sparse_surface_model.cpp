#include <pcl_sparse/model/sparse_surface_model.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/mesh/bounding_box.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pcl_sparse
{
  double
  PatchFootprint::extentAt (double angle) const
  {
    const int k = static_cast<int> (extent.size ());
    if (k == 0)
      return 0.0;
    double t = angle / (2.0 * M_PI);
    t -= std::floor (t);
    const double position = t * k;
    const int i = static_cast<int> (position) % k;
    const double w = position - std::floor (position);
    return (1.0 - w) * extent[i] + w * extent[(i + 1) % k];
  }

  bool
  PatchFootprint::contains (double x, double y) const
  {
    const double r = std::hypot (x, y);
    return r <= extentAt (std::atan2 (y, x));
  }

  double
  PatchFootprint::largestExtent () const
  {
    double largest = 0.0;
    for (float e : extent)
      largest = std::max (largest, static_cast<double> (e));
    return largest;
  }

  std::size_t
  SparseSurfaceModel::numNonZeros () const
  {
    std::size_t nnz = 0;
    for (const auto& p : patches)
      nnz += p.atoms.size ();
    return nnz;
  }

  HeightSample
  SparseSurfaceModel::evaluate (std::size_t p, double x, double y) const
  {
    const PatchCode& code = patches[p];
    return basis->evaluateCode (code.atoms, code.coefficients, x, y);
  }

  int
  SparseSurfaceModel::attributeIndex (AttributeChannel channel) const
  {
    for (std::size_t c = 0; c < attribute_channels.size (); ++c)
      if (attribute_channels[c].channel == channel)
        return static_cast<int> (c);
    return -1;
  }

  double
  SparseSurfaceModel::evaluateAttribute (std::size_t p, std::size_t c, double x, double y) const
  {
    const AttributeChannelInfo& info = attribute_channels[c];
    const std::vector<SparseCode>& codes = patches[p].attributes;
    const double value =
        c < codes.size () && attribute_basis ? attribute_basis->evaluateCodeValue (codes[c].atoms, codes[c].coefficients, x, y) : 0.0;
    return std::min (info.upper, std::max (info.lower, value));
  }
} // namespace pcl_sparse

namespace pcl_sparse
{
  double
  PatchCode::boundHalfWidth () const
  {
    return std::max (1.0, footprint.largestExtent ());
  }

  double
  PatchCode::heightBound (const SurfaceBasis& basis) const
  {
    const double half_width = boundHalfWidth ();
    double bound = 0.0;
    for (std::size_t k = 0; k < atoms.size () && k < coefficients.size (); ++k)
      bound += std::abs (coefficients[k]) * basis.atomBound (atoms[k], half_width);
    return bound;
  }

  double
  SparseSurfaceModel::compressionRatio () const
  {
    return pcl_sparse::compressionRatio (patches.size (), numNonZeros (), num_input_vertices);
  }

  double
  compressionRatio (std::size_t num_patches, std::size_t num_nonzeros, std::size_t num_vertices)
  {
    if (num_vertices == 0)
      return 0.0;
    return (13.0 * num_patches + num_nonzeros) / (3.0 * num_vertices);
  }

  std::vector<Eigen::Vector3d>
  SparseSurfaceModel::reconstructVertices (std::size_t num_vertices) const
  {
    std::vector<Eigen::Vector3d> sum (num_vertices, Eigen::Vector3d::Zero ());
    std::vector<int> count (num_vertices, 0);
    for (const PatchCode& code : patches)
    {
      const std::size_t n = std::min (code.vertices.size (), code.vertex_xy.size ());
      for (std::size_t k = 0; k < n; ++k)
      {
        const int v = code.vertices[k];
        if (v < 0 || static_cast<std::size_t> (v) >= num_vertices)
          continue;
        const Eigen::Vector2d& xy = code.vertex_xy[k];
        const double h = basis ? basis->evaluateCodeValue (code.atoms, code.coefficients, xy.x (), xy.y ()) : 0.0;
        sum[v] += code.toWorld (Eigen::Vector3d (xy.x (), xy.y (), h));
        ++count[v];
      }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN ();
    for (std::size_t v = 0; v < num_vertices; ++v)
      sum[v] = count[v] > 0 ? Eigen::Vector3d (sum[v] / count[v]) : Eigen::Vector3d (nan, nan, nan);
    return sum;
  }

  Eigen::MatrixXf
  SparseSurfaceModel::reconstructVertexAttributes (std::size_t num_vertices) const
  {
    const Eigen::Index channels = static_cast<Eigen::Index> (attribute_channels.size ());
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero (static_cast<Eigen::Index> (num_vertices), channels);
    std::vector<int> count (num_vertices, 0);
    for (std::size_t p = 0; p < patches.size (); ++p)
    {
      const PatchCode& code = patches[p];
      const std::size_t n = std::min (code.vertices.size (), code.vertex_xy.size ());
      for (std::size_t k = 0; k < n; ++k)
      {
        const int v = code.vertices[k];
        if (v < 0 || static_cast<std::size_t> (v) >= num_vertices)
          continue;
        for (Eigen::Index c = 0; c < channels; ++c)
          sum (v, c) += evaluateAttribute (p, static_cast<std::size_t> (c), code.vertex_xy[k].x (), code.vertex_xy[k].y ());
        ++count[v];
      }
    }
    for (std::size_t v = 0; v < num_vertices; ++v)
      sum.row (static_cast<Eigen::Index> (v)) /= count[v] > 0 ? count[v] : std::numeric_limits<double>::quiet_NaN ();
    return sum.cast<float> ();
  }

  ModelStatistics
  SparseSurfaceModel::statistics (const std::vector<Eigen::Vector3d>& input_vertices, std::vector<double>* errors) const
  {
    ModelStatistics stats;
    stats.num_vertices = input_vertices.size ();
    stats.num_patches = patches.size ();
    stats.num_nonzeros = numNonZeros ();
    stats.compression_ratio =
        stats.num_vertices > 0 ? (13.0 * stats.num_patches + stats.num_nonzeros) / (3.0 * stats.num_vertices) : 0.0;
    const std::vector<Eigen::Vector3d> reconstructed = reconstructVertices (input_vertices.size ());
    if (errors)
      errors->assign (input_vertices.size (), 0.0);
    double sum = 0.0, sum_abs = 0.0;
    std::size_t covered = 0;
    for (std::size_t v = 0; v < input_vertices.size (); ++v)
    {
      if (!reconstructed[v].allFinite ())
      {
        ++stats.uncovered;
        continue;
      }
      const double e = (reconstructed[v] - input_vertices[v]).norm ();
      if (errors)
        (*errors)[v] = e;
      sum += e * e;
      sum_abs += e;
      stats.max_error = std::max (stats.max_error, e);
      ++covered;
    }
    stats.rmse = covered > 0 ? std::sqrt (sum / covered) : 0.0;
    const double diagonal = bbox_diagonal > 0.0 ? bbox_diagonal : boundingBoxDiagonal (input_vertices);
    stats.rmse_over_diagonal = diagonal > 0.0 ? stats.rmse / diagonal : 0.0;
    stats.mean_error_over_diagonal = diagonal > 0.0 && covered > 0 ? sum_abs / covered / diagonal : 0.0;
    return stats;
  }
  void
  SparseSurfaceModel::translate (const Eigen::Vector3d& offset)
  {
    for (PatchCode& patch : patches)
      patch.origin += offset;
  }

  void
  SparseSurfaceModel::checkPatches (const std::string& who) const
  {
    const int basis_size = basis ? basis->size () : 0;
    auto requireFinite = [&] (double v, const std::string& what) {
      if (!std::isfinite (v))
        throw Error (who + what + " is not finite");
    };
    std::vector<bool> used (static_cast<std::size_t> (basis_size), false);
    for (std::size_t p = 0; p < patches.size (); ++p)
    {
      const PatchCode& patch = patches[p];
      const std::string name = "patch " + std::to_string (p);
      for (int i = 0; i < 3; ++i)
        requireFinite (patch.origin[i], name + " origin");
      for (int i = 0; i < 9; ++i)
        requireFinite (patch.frame (i), name + " frame");
      const double off = (patch.frame.transpose () * patch.frame - Eigen::Matrix3d::Identity ()).cwiseAbs ().maxCoeff ();
      if (!(off <= 1e-6))
        throw Error (who + name + " frame is not orthonormal");
      requireFinite (patch.radius, name + " radius");
      if (!(patch.radius > 0.0))
        throw Error (who + name + " radius is not positive");
      if (patch.atoms.size () != patch.coefficients.size ())
        throw Error (who + name + " has " + std::to_string (patch.atoms.size ()) + " atoms but " +
                     std::to_string (patch.coefficients.size ()) + " coefficients");
      if (patch.atoms.size () > static_cast<std::size_t> (basis_size))
        throw Error (who + name + " has more atoms than the basis");
      std::fill (used.begin (), used.end (), false);
      for (int a : patch.atoms)
      {
        if (a < 0 || a >= basis_size)
          throw Error (who + name + " has atom index " + std::to_string (a) + " outside the basis");
        if (used[a])
          throw Error (who + name + " repeats atom " + std::to_string (a));
        used[a] = true;
      }
      for (double c : patch.coefficients)
        requireFinite (c, name + " coefficient");
      for (float e : patch.footprint.extent)
        if (!std::isfinite (e) || e < 0.0f)
          throw Error (who + name + " footprint extent is negative or not finite");
    }
    checkAttributeCodes (who);
  }

  void
  SparseSurfaceModel::checkAttributeCodes (const std::string& who) const
  {
    if (!hasAttributes ())
    {
      for (std::size_t p = 0; p < patches.size (); ++p)
        if (!patches[p].attributes.empty ())
          throw Error (who + "patch " + std::to_string (p) + " has attribute codes but the model has no attribute channels");
      return;
    }
    if (!attribute_basis)
      throw Error (who + "the model has attribute channels but no attribute basis");
    const int basis_size = attribute_basis->size ();
    std::vector<bool> seen (num_attribute_channels, false);
    for (const AttributeChannelInfo& info : attribute_channels)
    {
      const int id = static_cast<int> (info.channel);
      if (id < 0 || id >= num_attribute_channels || seen[id])
        throw Error (who + "attribute channel " + std::to_string (id) + " unknown or repeated");
      seen[id] = true;
      if (!std::isfinite (info.lower) || !std::isfinite (info.upper) || info.lower > info.upper)
        throw Error (who + "attribute channel range is not finite or empty");
    }
    std::vector<bool> used (static_cast<std::size_t> (basis_size), false);
    for (std::size_t p = 0; p < patches.size (); ++p)
    {
      const std::vector<SparseCode>& codes = patches[p].attributes;
      const std::string name = "patch " + std::to_string (p);
      if (codes.size () != attribute_channels.size ())
        throw Error (who + name + " has " + std::to_string (codes.size ()) + " attribute codes for " +
                     std::to_string (attribute_channels.size ()) + " channels");
      for (const SparseCode& code : codes)
      {
        if (code.atoms.size () != code.coefficients.size () || code.atoms.size () > static_cast<std::size_t> (basis_size))
          throw Error (who + name + " attribute code has mismatched or too many atoms");
        std::fill (used.begin (), used.end (), false);
        for (int a : code.atoms)
        {
          if (a < 0 || a >= basis_size || used[a])
            throw Error (who + name + " attribute atom " + std::to_string (a) + " outside the basis or repeated");
          used[a] = true;
        }
        for (double c : code.coefficients)
          if (!std::isfinite (c))
            throw Error (who + name + " attribute coefficient is not finite");
      }
    }
  }
} // namespace pcl_sparse
