#include <pcl_sparse/resampling/impl/sparse_surface_resampling.hpp>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/resampling/patch_geometry.h>

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <numeric>
#include <sstream>

namespace pcl_sparse
{
  namespace
  {
    /// splitmix64 finaliser: a stateless hash, so a random number is a function of (seed, patch, cell,
    /// draw) and the result does not depend on the order patches are processed in. (A per-patch
    /// std::mt19937 would cost more to seed than drawing a small patch's points.)
    inline std::uint64_t
    mix (std::uint64_t z)
    {
      z += 0x9e3779b97f4a7c15ULL;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      return z ^ (z >> 31);
    }

    /// Uniform in [0, 1) from (key, index).
    inline double
    uniform (std::uint64_t key, std::uint64_t index)
    {
      return static_cast<double> (mix (key ^ mix (index)) >> 11) * 0x1.0p-53;
    }

    /// Key of patch \a p in pass \a pass for \a seed.
    inline std::uint64_t
    patchKey (std::uint64_t seed, std::size_t p, std::uint64_t pass)
    {
      return mix (mix (seed) ^ mix (static_cast<std::uint64_t> (p) * 4 + pass));
    }

    /// A candidate place kept by its patch: local position, area weight sqrt(1 + |grad h|^2) and cell.
    struct Candidate
    {
      float x, y, weight;
      std::int32_t cell;
      std::int32_t evaluated;  ///< index of its already evaluated point, or -1
    };

    using Points = SparseSurfaceResamplingBase::PointCloud::VectorType;

    /// The stratification grid of one patch: n x n cells of side `cell` centred on the seed.
    struct PatchGrid
    {
      double cell = 1.0;
      int n = 1;
      double start = 0.0;
    };

    PatchGrid
    makeGrid (double max_extent, double cell)
    {
      PatchGrid grid;
      grid.cell = cell;
      grid.n = std::max (1, static_cast<int> (std::ceil (2.0 * max_extent / cell)));
      grid.start = -0.5 * grid.n * cell;
      return grid;
    }

    class PatchSampler
    {
    public:
      PatchSampler (const PatchEvaluator& evaluator, const PatchOwnership& ownership, double jitter, double max_weight)
        : model_ (evaluator.model ()), evaluator_ (evaluator), ownership_ (ownership), jitter_ (jitter), max_weight_ (max_weight)
      {}

      /// Whether patch \a p keeps the place (x, y): inside its footprint and owned by it. Only the height
      /// is evaluated here; the caller evaluates derivatives for the places kept.
      bool
      keeps (std::size_t p, double x, double y) const
      {
        double turn;
        const double c = evaluator_.centrality (p, x, y, turn);
        if (c > 1.0)
          return false;
        const double z = evaluator_.height (p, x, y);
        if (!(std::abs (z) <= ownership_.options ().max_height))
          return false;
        return ownership_.owns (p, model_.patches[p].toWorld (Eigen::Vector3d (x, y, z)), c, turn);
      }

      /// Weight of the place (x, y) of patch \a p: its capped area element if p keeps it and its code is
      /// valid there, 0 otherwise. \a h gets the Hessian only when \a hessian is set (for makePoint).
      double
      placeWeight (std::size_t p, double x, double y, HeightSample& h, bool hessian = false) const
      {
        if (!keeps (p, x, y))
          return 0.0;
        h = evaluator_.sample (p, x, y, hessian);
        if (!isValidPlace (h, ownership_.options (), ownership_.maxSlopeSquared ()))
          return 0.0;
        return std::min (max_weight_, std::sqrt (1.0 + h.gradient.squaredNorm ()));
      }

      /// The output point of patch \a p at (x, y) with height sample \a h.
      void
      makePoint (std::size_t p, double x, double y, const HeightSample& h, pcl::PointNormal& point) const
      {
        const PatchCode& code = model_.patches[p];
        const Eigen::Vector3d position = patchPoint (code, x, y, h);
        const Eigen::Vector3d normal = patchNormal (code, h);
        point.x = static_cast<float> (position.x ());
        point.y = static_cast<float> (position.y ());
        point.z = static_cast<float> (position.z ());
        point.normal_x = static_cast<float> (normal.x ());
        point.normal_y = static_cast<float> (normal.y ());
        point.normal_z = static_cast<float> (normal.z ());
        point.curvature = static_cast<float> (patchMeanCurvature (code, h));
      }

      /// At high density most cells lie well inside or well outside the part a patch keeps. A quadtree over
      /// the cell corners finds them: a block whose four corners agree is taken whole (kept cells get the
      /// bilinear weight of the corners), a block whose corners disagree is split, down to single cells
      /// that are tested candidate by candidate. Blocks start at 1/8 of the grid (a quarter of the
      /// footprint radius), far smaller than the curvature of ownership borders and footprints.
      /// \a cells receives per cell: 0 dropped, > 0 kept with that weight, < 0 to be tested.
      /// Returns false (and leaves \a cells empty) when the grid is too coarse for blocks to pay.
      bool
      classifyCells (std::size_t p, const PatchGrid& grid, std::vector<float>& cells, std::vector<float>& nodes) const
      {
        const int n = grid.n;
        int top = 1;
        while (top * 2 <= n / 8)
          top *= 2;
        cells.clear ();
        if (top < 4)
          return false;
        const int stride = n + 1;
        nodes.assign (static_cast<std::size_t> (stride) * stride, -1.0f);
        cells.assign (static_cast<std::size_t> (n) * n, -1.0f);
        auto node = [&] (int a, int b) {
          float& w = nodes[static_cast<std::size_t> (b) * stride + a];
          if (w < 0.0f)
          {
            HeightSample h;
            w = static_cast<float> (placeWeight (p, grid.start + a * grid.cell, grid.start + b * grid.cell, h));
          }
          return static_cast<double> (w);
        };
        std::vector<std::array<int, 3>> stack;
        for (int j = 0; j < n; j += top)
          for (int i = 0; i < n; i += top)
            stack.push_back ({i, j, top});
        while (!stack.empty ())
        {
          const auto [i0, j0, size] = stack.back ();
          stack.pop_back ();
          const int i1 = std::min (i0 + size, n), j1 = std::min (j0 + size, n);
          const double w00 = node (i0, j0), w10 = node (i1, j0), w01 = node (i0, j1), w11 = node (i1, j1);
          const bool all_in = w00 > 0.0 && w10 > 0.0 && w01 > 0.0 && w11 > 0.0;
          const bool all_out = w00 == 0.0 && w10 == 0.0 && w01 == 0.0 && w11 == 0.0;
          if (!all_in && !all_out)
          {
            if (size > 1)
            {
              const int half = size / 2;
              for (int dj = 0; dj < size; dj += half)
                for (int di = 0; di < size; di += half)
                  if (i0 + di < n && j0 + dj < n)
                    stack.push_back ({i0 + di, j0 + dj, half});
            }
            continue;  // single mixed cells stay -1: tested candidate by candidate
          }
          for (int j = j0; j < j1; ++j)
            for (int i = i0; i < i1; ++i)
            {
              float& cell = cells[static_cast<std::size_t> (j) * n + i];
              if (all_out)
                cell = 0.0f;
              else
              {
                const double u = (i + 0.5 - i0) / (i1 - i0), v = (j + 0.5 - j0) / (j1 - j0);
                cell = static_cast<float> ((1 - u) * (1 - v) * w00 + u * (1 - v) * w10 + (1 - u) * v * w01 + u * v * w11);
              }
            }
        }
        return true;
      }

      /// One jittered candidate per cell, kept ones in serpentine cell order; returns their weight sum.
      /// Candidates tested one by one keep their evaluated point in \a evaluated, for the selection.
      double
      drawCandidates (std::size_t p, const PatchGrid& grid, std::uint64_t key, std::vector<Candidate>& out,
                      Points& evaluated) const
      {
        out.clear ();
        evaluated.clear ();
        std::vector<float> cells, nodes;
        const bool classified = classifyCells (p, grid, cells, nodes);
        // One allocation per patch instead of a doubling series (copies and page faults): at most the
        // cells not dropped by the classification keep a candidate.
        out.reserve (classified ? static_cast<std::size_t> (std::count_if (cells.begin (), cells.end (), [] (float c) { return c != 0.0f; }))
                                : static_cast<std::size_t> (grid.n) * grid.n);
        double sum = 0.0;
        for (int row = 0; row < grid.n; ++row)
          for (int k = 0; k < grid.n; ++k)
          {
            const int col = (row % 2 == 0) ? k : grid.n - 1 - k;
            const std::int32_t cell = row * grid.n + col;
            const float state = classified ? cells[cell] : -1.0f;
            if (state == 0.0f)
              continue;
            const double x = grid.start + (col + 0.5 + jitter_ * (uniform (key, 2 * cell) - 0.5)) * grid.cell;
            const double y = grid.start + (row + 0.5 + jitter_ * (uniform (key, 2 * cell + 1) - 0.5)) * grid.cell;
            std::int32_t index = -1;
            double w = state;
            if (state < 0.0f)
            {
              HeightSample h;
              w = placeWeight (p, x, y, h, true);
              if (w == 0.0)
                continue;
              index = static_cast<std::int32_t> (evaluated.size ());
              evaluated.emplace_back ();
              makePoint (p, x, y, h, evaluated.back ());
            }
            out.push_back ({static_cast<float> (x), static_cast<float> (y), static_cast<float> (w), cell, index});
            sum += w;
          }
        return sum;
      }

      /// Exactly \a count points from \a candidates by systematic sampling of their cumulative weight.
      /// With \a attributes (optional), also each point's attribute channels, C per point.
      void
      selectPoints (std::size_t p, const PatchGrid& grid, std::uint64_t key, const std::vector<Candidate>& candidates,
                    const Points& evaluated, std::size_t count, pcl::PointNormal* out, float* attributes) const
      {
        if (count == 0 || candidates.empty ())
          return;
        double total = 0.0;
        for (const Candidate& c : candidates)
          total += c.weight;
        const double step = total / static_cast<double> (count);
        double t = uniform (key, ~0ULL) * step;
        double cumulative = 0.0;
        const std::uint64_t cells = static_cast<std::uint64_t> (grid.n) * grid.n;
        std::size_t emitted = 0;
        // The first point of a cell not yet evaluated (most points) waits in a block of places evaluated
        // together; the others (evaluated with the candidate, or redrawn in the cell) are made at once.
        PointBlock block;
        for (std::size_t k = 0; k < candidates.size () && emitted < count; ++k)
        {
          const Candidate& c = candidates[k];
          const double high = (k + 1 == candidates.size ()) ? std::numeric_limits<double>::infinity () : cumulative + c.weight;
          for (int draw = 0; t < high && emitted < count; ++draw, t += step)
          {
            Eigen::Vector2d xy (c.x, c.y);
            if (draw == 0 && c.evaluated >= 0)
              out[emitted] = evaluated[c.evaluated];
            else if (draw == 0)
              block.add (*this, p, xy.x (), xy.y (), out + emitted);
            else
              xy = emit (p, grid, key, c, draw, cells, out[emitted]);
            if (attributes)
              attributesAt (p, xy, attributes + emitted * model_.attribute_channels.size ());
            ++emitted;
          }
          cumulative = high;
        }
        block.flush (*this, p);
      }

    private:
      /// Places waiting for their point, evaluated a block at a time (PatchEvaluator::sampleBlock).
      struct PointBlock
      {
        PatchEvaluator::Block places;
        pcl::PointNormal* targets[PatchEvaluator::Block::size];
        int filled = 0;

        void
        add (const PatchSampler& sampler, std::size_t p, double x, double y, pcl::PointNormal* target)
        {
          places.x[filled] = x;
          places.y[filled] = y;
          targets[filled] = target;
          if (++filled == PatchEvaluator::Block::size)
            flush (sampler, p);
        }

        void
        flush (const PatchSampler& sampler, std::size_t p)
        {
          if (filled == 0)
            return;
          sampler.evaluator_.sampleBlock (p, places);
          for (int b = 0; b < filled; ++b)
            sampler.makePoint (p, places.x[b], places.y[b], places.sample (b), *targets[b]);
          filled = 0;
        }
      };

      /// Every attribute channel of patch \a p at local \a xy.
      void
      attributesAt (std::size_t p, const Eigen::Vector2d& xy, float* values) const
      {
        for (std::size_t c = 0; c < model_.attribute_channels.size (); ++c)
          values[c] = static_cast<float> (model_.evaluateAttribute (p, c, xy.x (), xy.y ()));
      }

      /// The first point of a cell is its candidate; further ones are fresh places in the same cell.
      /// Returns the local (x, y) of the point.
      Eigen::Vector2d
      emit (std::size_t p, const PatchGrid& grid, std::uint64_t key, const Candidate& c, int draw, std::uint64_t cells,
            pcl::PointNormal& point) const
      {
        double x = c.x, y = c.y;
        HeightSample h;
        bool found = false;
        if (draw > 0)
        {
          const int row = c.cell / grid.n, col = c.cell % grid.n;
          for (int attempt = 0; attempt < 8 && !found; ++attempt)
          {
            const std::uint64_t index = 2 * (cells * (8 * static_cast<std::uint64_t> (draw) + attempt) + c.cell);
            const double xa = grid.start + (col + uniform (key, index)) * grid.cell;
            const double ya = grid.start + (row + uniform (key, index + 1)) * grid.cell;
            if (placeWeight (p, xa, ya, h) > 0.0)
            {
              x = xa;
              y = ya;
              found = true;
            }
          }
        }
        h = evaluator_.sample (p, x, y);
        makePoint (p, x, y, h, point);
        return Eigen::Vector2d (x, y);
      }

      const SparseSurfaceModel& model_;
      const PatchEvaluator& evaluator_;
      const PatchOwnership& ownership_;
      double jitter_;
      double max_weight_;
    };

    /// Largest-remainder split of \a total into parts proportional to \a weights.
    std::vector<std::size_t>
    largestRemainder (const std::vector<double>& weights, std::size_t total)
    {
      const double sum = std::accumulate (weights.begin (), weights.end (), 0.0);
      std::vector<std::size_t> parts (weights.size (), 0);
      std::vector<std::pair<double, std::size_t>> remainders;
      std::size_t given = 0;
      for (std::size_t i = 0; i < weights.size (); ++i)
      {
        if (weights[i] <= 0.0)
          continue;
        const double exact = static_cast<double> (total) * weights[i] / sum;
        parts[i] = static_cast<std::size_t> (std::floor (exact));
        given += parts[i];
        remainders.emplace_back (exact - std::floor (exact), i);
      }
      // Larger remainder first, lower index on ties: deterministic.
      std::sort (remainders.begin (), remainders.end (), [] (const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
      });
      for (std::size_t k = 0; given < total && !remainders.empty (); ++k, ++given)
        ++parts[remainders[k % remainders.size ()].second];
      return parts;
    }
  } // namespace

  /// The tables and per-patch results the passes share.
  struct SparseSurfaceResamplingBase::Passes
  {
    Passes (const PatchEvaluator& evaluator, const PatchOwnership& ownership, const SparseSurfaceResamplingOptions& options,
            std::size_t m)
      : sampler (evaluator, ownership, options.jitter, options.max_area_weight), candidates (m), evaluated (m),
        weights (m, 0.0), grids (m)
    {}

    const PatchSampler sampler;
    std::vector<std::vector<Candidate>> candidates;
    std::vector<Points> evaluated;
    std::vector<double> weights;
    std::vector<PatchGrid> grids;
  };

  void
  SparseSurfaceResamplingBase::setInputModel (const SparseSurfaceModel::ConstPtr& model)
  {
    // The tables of the previous model are dropped even for the same pointer: it may have changed.
    ownership_.reset ();
    evaluator_.reset ();
    model_ = model;
  }

  void
  SparseSurfaceResamplingBase::setPointCount (std::size_t count)
  {
    if (count == 0 || count > max_points)
      throw Error (name_ + ": point count must be in [1, " + std::to_string (max_points) + "], got " +
                   std::to_string (count));
    mode_ = Mode::Count;
    count_ = count;
  }

  void
  SparseSurfaceResamplingBase::setDensity (double density)
  {
    if (!(density > 0.0) || !std::isfinite (density))
      throw Error (name_ + ": density must be a positive number of points per unit area");
    mode_ = Mode::Density;
    density_ = density;
  }

  void
  SparseSurfaceResamplingBase::setSpacing (double spacing)
  {
    if (!(spacing > 0.0) || !std::isfinite (spacing))
      throw Error (name_ + ": spacing must be a positive length");
    setDensity (1.0 / (spacing * spacing));
  }

  void
  SparseSurfaceResamplingBase::resample (PointCloud& output, bool with_attributes)
  {
    with_attributes_ = with_attributes;
    if (!model_)
      throw Error (name_ + "::compute: no input model (setInputModel)");
    if (!model_->basis)
      throw Error (name_ + "::compute: the model has no basis");
    if (model_->patches.empty ())
      throw Error (name_ + "::compute: the model has no patches");
    if (mode_ == Mode::None)
      throw Error (name_ + "::compute: no density given (setPointCount, setDensity or setSpacing)");
    if (!(options_.jitter >= 0.0 && options_.jitter <= 1.0))
      throw Error (name_ + "::compute: jitter must be in [0, 1]");
    if (!(options_.max_area_weight >= 1.0))
      throw Error (name_ + "::compute: max_area_weight must be at least 1");
    for (const PatchCode& code : model_->patches)
      if (!(code.radius > 0.0) || !std::isfinite (code.radius))
        throw Error (name_ + "::compute: a patch has a non-positive radius");
    if (!patch_numbers_.empty () && patch_numbers_.size () != model_->patches.size ())
      throw Error (name_ + "::compute: " + std::to_string (patch_numbers_.size ()) + " patch numbers for " +
                   std::to_string (model_->patches.size ()) + " patches");
    computeResampling (output);
  }

  double
  SparseSurfaceResamplingBase::densityForCount () const
  {
    // The area pass costs what a candidate pass at its density costs: at most area_pass_cells cells
    // per patch, and at most a quarter of the final pass's cells (guessed from the footprint areas with
    // an overlap of 2), since with few points per patch a fixed 64 cells would cost more than the rest.
    const SparseSurfaceModel& model = *model_;
    const std::size_t m = model.numPatches ();
    const PatchSampler sampler (*evaluator_, *ownership_, options_.jitter, options_.max_area_weight);
    double footprint_area = 0.0;
    for (const PatchCode& code : model.patches)
    {
      double square = 0.0;
      for (float e : code.footprint.extent)
        square += static_cast<double> (e) * e;
      square = code.footprint.extent.empty () ? 1.0 : square / code.footprint.extent.size ();
      footprint_area += M_PI * square * code.radius * code.radius;
    }
    const double guess = static_cast<double> (count_) / (0.5 * footprint_area);
    std::vector<double> areas (m, 0.0);
    const double cells_per_axis = std::sqrt (std::max (1, options_.area_pass_cells));
#pragma omp parallel for schedule(dynamic, 8) num_threads(threadsToUse ())
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      const double e = evaluator_->maxExtent (p);
      const double final_cell = 1.0 / (model.patches[p].radius * std::sqrt (guess));
      const PatchGrid grid = makeGrid (e, std::min (e, std::max (2.0 * e / cells_per_axis, 2.0 * final_cell)));
      std::vector<Candidate> candidates;
      Points evaluated;
      const double r = model.patches[p].radius;
      areas[p] = sampler.drawCandidates (p, grid, patchKey (options_.seed, patchNumber (p), 0), candidates, evaluated) * grid.cell *
                 grid.cell * r * r;
    }
    const double area = std::accumulate (areas.begin (), areas.end (), 0.0);
    if (!(area > 0.0))
      throw Error (name_ + "::compute: the model has no surface area to sample");
    return static_cast<double> (count_) / area;
  }

  void
  SparseSurfaceResamplingBase::checkDensityBound (double density) const
  {
    // Every grid square bounds its patch's candidates.
    double bound = 0.0;
    for (std::size_t p = 0; p < model_->numPatches (); ++p)
    {
      const double side = 2.0 * evaluator_->maxExtent (p) * model_->patches[p].radius;
      bound += side * side * density;
    }
    if (bound > 4.0 * static_cast<double> (max_points))
    {
      std::ostringstream message;
      message << name_ << "::compute: density " << density << " would give about " << bound / 4.0
              << " points, more than the limit " << max_points;
      throw Error (message.str ());
    }
  }

  void
  SparseSurfaceResamplingBase::drawAllCandidates (double& density, Passes& passes, PointCloud* prefill) const
  {
    // Every patch's kept places and owned area at the final density. With a total count, cells hold one
    // point each only if the area pass was right: if the measured area differs by more than 2%, the pass
    // is redone once at the corrected density (systematic sampling at a step off by x% skips or doubles
    // every (100/x)-th cell, which shows in the spacing). A count so small that no cell keeps a candidate
    // also retries, at 4 x the density.
    const std::size_t m = model_->numPatches ();
    const int threads = threadsToUse ();
    std::atomic<std::size_t> done (0);
    for (int attempt = 0, corrections = 0; attempt < 16; ++attempt)
    {
      done = 0;
      std::exception_ptr failure;
#pragma omp parallel num_threads(threads)
      {
#pragma omp single nowait
        if (prefill && attempt == 0)
          try
          {
            prefill->clear ();
            prefill->resize (count_);
          }
          catch (...)
          {
            failure = std::current_exception ();
          }
#pragma omp for schedule(dynamic, 4)
        for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
        {
          const std::size_t p = static_cast<std::size_t> (pi);
          const double r = model_->patches[p].radius;
          passes.grids[p] = makeGrid (evaluator_->maxExtent (p), 1.0 / (r * std::sqrt (density)));
          passes.weights[p] = passes.sampler.drawCandidates (p, passes.grids[p], patchKey (options_.seed, patchNumber (p), 1),
                                                            passes.candidates[p], passes.evaluated[p]);
          const std::size_t finished = ++done;
          if (progress_ && omp_get_thread_num () == 0)
            progress_ ("resample", 0.5 * static_cast<double> (finished) / static_cast<double> (m));
        }
      }
      if (failure)
        std::rethrow_exception (failure);
      if (mode_ != Mode::Count)
        break;
      const double expected = std::accumulate (passes.weights.begin (), passes.weights.end (), 0.0);
      if (!(expected > 0.0))
      {
        density *= 4.0;
        continue;
      }
      const double ratio = static_cast<double> (count_) / expected;
      if (std::abs (ratio - 1.0) <= 0.02 || corrections++ > 0)
        break;
      density *= ratio;
    }
  }

  std::vector<std::size_t>
  SparseSurfaceResamplingBase::pointsPerPatch (const std::vector<double>& weights) const
  {
    if (mode_ == Mode::Count)
      return largestRemainder (weights, count_);
    std::vector<std::size_t> counts (weights.size (), 0);
    double total = 0.0;
    for (std::size_t p = 0; p < weights.size (); ++p)
    {
      const double whole = std::floor (weights[p]);
      counts[p] = static_cast<std::size_t> (whole) + (uniform (patchKey (options_.seed, patchNumber (p), 2), 0) < weights[p] - whole ? 1 : 0);
      total += static_cast<double> (counts[p]);
    }
    if (total > static_cast<double> (max_points))
      throw Error (name_ + "::compute: density gives more than " + std::to_string (max_points) + " points");
    return counts;
  }

  void
  SparseSurfaceResamplingBase::selectAllPoints (const std::vector<std::size_t>& counts, Passes& passes, PointCloud& output,
                                                bool prefilled)
  {
    const std::size_t m = counts.size ();
    std::vector<std::size_t> offsets (m + 1, 0);
    for (std::size_t p = 0; p < m; ++p)
      offsets[p + 1] = offsets[p] + counts[p];
    // Every point is written below; a prefilled cloud holds freshly constructed points, as resize gives.
    if (!prefilled || output.size () != offsets[m])
    {
      output.clear ();
      output.resize (offsets[m]);
    }
    point_patches_.assign (offsets[m], 0);
    const std::size_t channels = with_attributes_ ? model_->attribute_channels.size () : 0;
    point_attributes_.assign (offsets[m] * channels, 0.0f);
    std::atomic<std::size_t> done (0);
#pragma omp parallel for schedule(dynamic, 4) num_threads(threadsToUse ())
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
    {
      const std::size_t p = static_cast<std::size_t> (pi);
      passes.sampler.selectPoints (p, passes.grids[p], patchKey (options_.seed, patchNumber (p), 3), passes.candidates[p],
                                   passes.evaluated[p], counts[p], output.data () + offsets[p],
                                   channels > 0 ? point_attributes_.data () + offsets[p] * channels : nullptr);
      std::fill (point_patches_.begin () + offsets[p], point_patches_.begin () + offsets[p + 1], static_cast<int> (p));
      std::vector<Candidate> ().swap (passes.candidates[p]);
      Points ().swap (passes.evaluated[p]);
      const std::size_t finished = ++done;
      if (progress_ && omp_get_thread_num () == 0)
        progress_ ("resample", 0.5 + 0.5 * static_cast<double> (finished) / static_cast<double> (m));
    }
    output.width = static_cast<std::uint32_t> (output.size ());
    output.height = 1;
    output.is_dense = true;
  }

  void
  SparseSurfaceResamplingBase::computeResampling (PointCloud& output)
  {
    if (!evaluator_)
      evaluator_ = std::make_shared<PatchEvaluator> (*model_);
    if (!ownership_)
      ownership_ = std::make_shared<PatchOwnership> (*evaluator_, options_.ownership, threadsToUse ());

    // Density: given, or from a coarse area pass when a total count is asked for.
    double density = mode_ == Mode::Count ? densityForCount () : density_;
    checkDensityBound (density);
    Passes passes (*evaluator_, *ownership_, options_, model_->numPatches ());
    // With a count, the cloud's size is known: its construction overlaps the candidate pass.
    const bool prefill = mode_ == Mode::Count;
    drawAllCandidates (density, passes, prefill ? &output : nullptr);
    const double weight = std::accumulate (passes.weights.begin (), passes.weights.end (), 0.0);
    if (!(weight > 0.0))
      throw Error (name_ + "::compute: the model has no surface area to sample");
    // A cell holds one expected point on flat ground, so weights are areas in units of 1 / density.
    estimated_area_ = weight / density;
    density_used_ = density;
    selectAllPoints (pointsPerPatch (passes.weights), passes, output, prefill);
    if (progress_)
      progress_ ("resample", 1.0);
  }

#define PCL_SPARSE_INSTANTIATE_RESAMPLING(T) template class SparseSurfaceResampling<T>;
  PCL_SPARSE_FOR_EACH_OUTPUT_POINT_TYPE (PCL_SPARSE_INSTANTIATE_RESAMPLING)
#undef PCL_SPARSE_INSTANTIATE_RESAMPLING
} // namespace pcl_sparse
