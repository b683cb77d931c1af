#include <pcl_sparse/resampling/impl/sparse_surface_resampling.hpp>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/huge_pages.h>
#include <pcl_sparse/common/memory_limit.h>
#include <pcl_sparse/common/parallel_failure.h>
#include <pcl_sparse/common/splitmix64.h>
#include <pcl_sparse/mesh/bounding_box.h>
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
    /// Uniform in [0, 1) from (key, index). A random number is a function of (seed, patch, cell, draw), so
    /// the result does not depend on the order patches are processed in. (A per-patch std::mt19937 would
    /// cost more to seed than drawing a small patch's points.)
    inline double
    uniform (std::uint64_t key, std::uint64_t index)
    {
      return static_cast<double> (splitmix64 (key ^ splitmix64 (index)) >> 11) * 0x1.0p-53;
    }

    /// Key of patch \a p in pass \a pass for \a seed.
    inline std::uint64_t
    patchKey (std::uint64_t seed, std::size_t p, std::uint64_t pass)
    {
      return splitmix64 (splitmix64 (seed) ^ splitmix64 (static_cast<std::uint64_t> (p) * 4 + pass));
    }

    /// A candidate place kept by its patch: local position, area weight sqrt(1 + |grad h|^2) and cell.
    struct Candidate
    {
      float x, y, weight;
      std::uint32_t cell;  ///< row * n + col
      std::int32_t evaluated;  ///< index of its already evaluated point, or -1
    };

    using Points = SparseSurfaceResamplingBase::PointCloud::VectorType;

    /// The stratification grid of one patch: n x n cells of side `cell` centred on the seed.
    struct PatchGrid
    {
      double cell = 1.0;
      int n = 1;
      double start = 0.0;
      double weight = 1.0;  ///< area of a cell in units of the cell asked for (below 1 on a patch too small for it)
    };

    /// Fewest cells along a patch's grid. A candidate jitters within the middle of its cell, so a cell cut by
    /// the footprint's border keeps or drops its whole area: with a patch smaller than a cell, every patch
    /// whose middle lay inside kept a full cell of area (fandisk at 10 points per unit area: 122 points for
    /// 2.2 units^2), and 4 cells along a cap of the unit sphere still gave it an area of 10.8 or 16.7 by
    /// where the grid fell. Smaller cells, each weighing its share of the asked one, bound that to the
    /// border cells: 8 hold the area within 4 % at any density. The price, at 2 points a patch: the
    /// 99th-percentile gap grows from 0.86-0.90 to 0.89-0.95 spacings (a patch's few points spread less evenly).
    constexpr int min_grid_cells = 8;

    PatchGrid
    makeGrid (double max_extent, double cell)
    {
      // Cells are numbered row * n + col in 32 bits: n stays below 2^16. Only a patch owning a sliver of its
      // square at a density near max_points gets there.
      const double n = max_extent > 0.0 ? std::ceil (2.0 * max_extent / cell) : 1.0;  // a footprint of no extent: one cell
      if (!(n < 65536.0))
        throw Error ("SparseSurfaceResampling::compute: the density asks for more than 2^32 cells in one patch: lower it");
      PatchGrid grid;
      grid.cell = cell;
      grid.n = std::max (1, static_cast<int> (n));
      if (max_extent > 0.0 && grid.n < min_grid_cells)
      {
        grid.n = min_grid_cells;
        grid.cell = 2.0 * max_extent / min_grid_cells;
        grid.weight = (grid.cell / cell) * (grid.cell / cell);
      }
      grid.start = -0.5 * grid.n * grid.cell;
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

      /// Side, in cells, of the top blocks of the cell classification (a power of two, at most 1/8 of
      /// the grid); below 4 the grid is too coarse for blocks to pay and cells are tested one by one.
      static int
      topBlock (const PatchGrid& grid)
      {
        int top = 1;
        while (top * 2 <= grid.n / 8)
          top *= 2;
        return top;
      }

      /// At high density most cells lie well inside or well outside the part a patch keeps. A quadtree over
      /// the cell corners finds them: a block whose four corners agree is taken whole (kept cells get the
      /// bilinear weight of the corners) unless a small facing-away patch can clear places inside it, a block
      /// whose corners disagree is split, down to single cells
      /// that are tested candidate by candidate. Blocks start at \a top cells (1/8 of the grid or less: a
      /// quarter of the footprint radius), far smaller than the curvature of ownership borders and
      /// footprints. This classifies the rows [\a row0, \a row1) (a band of whole top blocks): \a cells
      /// receives per cell of the band, row after row: 0 dropped, > 0 kept with that weight, < 0 to be
      /// tested. \a nodes memoises the corner weights of node rows row0 .. row1; its first row may hold the
      /// previous band's last one (-1 where not evaluated). A node's weight does not depend on the band, so
      /// a grid classified band by band (bounded memory) is classified exactly as in one piece.
      void
      classifyBand (std::size_t p, const PatchGrid& grid, int top, int row0, int row1, std::vector<float>& cells,
                    std::vector<float>& nodes) const
      {
        const int n = grid.n;
        const int stride = n + 1;
        cells.assign (static_cast<std::size_t> (row1 - row0) * n, -1.0f);
        auto node = [&] (int a, int b) {
          float& w = nodes[static_cast<std::size_t> (b - row0) * stride + a];
          if (w < 0.0f)
          {
            HeightSample h;
            w = static_cast<float> (placeWeight (p, grid.start + a * grid.cell, grid.start + b * grid.cell, h));
          }
          return static_cast<double> (w);
        };
        // A small patch facing away can clear places lying between four kept corners: blocks its disk may
        // reach are split down to cells tested one by one. Disks of radius over two top blocks are left out:
        // splitting under them tests most of a patch's cells one by one (memory growing with the density),
        // and what they clear mostly reaches a corner; a thin band between corners stays unseen.
        std::vector<Eigen::Vector3d> opposite = ownership_.oppositeDisks (p);
        opposite.erase (std::remove_if (opposite.begin (), opposite.end (),
                                        [&] (const Eigen::Vector3d& disk) { return disk.z () > 2.0 * top * grid.cell; }),
                        opposite.end ());
        auto mayBeCleared = [&] (int i0, int j0, int i1, int j1) {
          const double x0 = grid.start + i0 * grid.cell, x1 = grid.start + i1 * grid.cell;
          const double y0 = grid.start + j0 * grid.cell, y1 = grid.start + j1 * grid.cell;
          for (const Eigen::Vector3d& disk : opposite)
          {
            const double dx = std::max ({x0 - disk.x (), 0.0, disk.x () - x1}), dy = std::max ({y0 - disk.y (), 0.0, disk.y () - y1});
            if (dx * dx + dy * dy <= disk.z () * disk.z ())
              return true;
          }
          return false;
        };
        std::vector<std::array<int, 3>> stack;
        for (int j = row0; j < row1; j += top)
          for (int i = 0; i < n; i += top)
            stack.push_back ({i, j, top});
        while (!stack.empty ())
        {
          const auto [i0, j0, size] = stack.back ();
          stack.pop_back ();
          const int i1 = std::min (i0 + size, n), j1 = std::min (j0 + size, n);
          const double w00 = node (i0, j0), w10 = node (i1, j0), w01 = node (i0, j1), w11 = node (i1, j1);
          const bool all_in = w00 > 0.0 && w10 > 0.0 && w01 > 0.0 && w11 > 0.0 && !mayBeCleared (i0, j0, i1, j1);
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
              float& cell = cells[static_cast<std::size_t> (j - row0) * n + i];
              if (all_out)
                cell = 0.0f;
              else
              {
                const double u = (i + 0.5 - i0) / (i1 - i0), v = (j + 0.5 - j0) / (j1 - j0);
                cell = static_cast<float> ((1 - u) * (1 - v) * w00 + u * (1 - v) * w10 + (1 - u) * v * w01 + u * v * w11);
              }
            }
        }
      }

      /// Cells classified at once, at most (4 MB of cell and node weights; larger grids go by bands of
      /// top blocks, so that memory stays bounded whatever the density).
      static constexpr std::size_t whole_grid_cells = std::size_t (1) << 19;

      /// One jittered candidate per cell, kept ones in serpentine cell order; returns their weight sum.
      /// Candidates tested one by one keep their evaluated point in \a evaluated, for the selection. With
      /// \a store false, only the sum is computed (the same sum) and \a out and \a evaluated stay empty;
      /// \a kept (optional) receives the number of candidates either way. \a expected (0: unknown) is the
      /// number of candidates, when a previous draw told it.
      double
      drawCandidates (std::size_t p, const PatchGrid& grid, std::uint64_t key, std::vector<Candidate>& out,
                      Points& evaluated, bool store = true, std::size_t* kept = nullptr, std::size_t expected = 0) const
      {
        out.clear ();
        evaluated.clear ();
        const int n = grid.n, top = topBlock (grid);
        const bool classified = top >= 4;
        // Whole grid when small enough (one allocation per patch instead of a doubling series: at most the
        // cells not dropped keep a candidate), else bands of top blocks.
        const std::size_t cells_total = static_cast<std::size_t> (n) * n;
        const int band = (!classified || cells_total <= whole_grid_cells) ? n : top;
        std::vector<float> cells, nodes;
        if (classified)
          nodes.assign (static_cast<std::size_t> (band + 1) * (n + 1), -1.0f);
        double sum = 0.0;
        std::size_t count = 0;
        for (int row0 = 0; row0 < n; row0 += band)
        {
          const int row1 = std::min (n, row0 + band);
          if (classified)
          {
            if (row0 > 0)
            {
              // The previous band's last node row is this band's first.
              std::copy (nodes.end () - (n + 1), nodes.end (), nodes.begin ());
              std::fill (nodes.begin () + (n + 1), nodes.end (), -1.0f);
            }
            classifyBand (p, grid, top, row0, row1, cells, nodes);
          }
          if (store && band == n)
            out.reserve (expected > 0 ? expected
                         : classified ? static_cast<std::size_t> (std::count_if (cells.begin (), cells.end (), [] (float c) { return c != 0.0f; }))
                                      : cells_total);
          else if (store && row0 == 0 && expected > 0)
            out.reserve (expected);
          for (int row = row0; row < row1; ++row)
            for (int k = 0; k < n; ++k)
            {
              const int col = (row % 2 == 0) ? k : n - 1 - k;
              const std::uint32_t cell = static_cast<std::uint32_t> (row) * static_cast<std::uint32_t> (n) + static_cast<std::uint32_t> (col);
              const float state = classified ? cells[static_cast<std::size_t> (row - row0) * n + col] : -1.0f;
              if (state == 0.0f)
                continue;
              const double x = grid.start + (col + 0.5 + jitter_ * (uniform (key, 2 * static_cast<std::uint64_t> (cell)) - 0.5)) * grid.cell;
              const double y = grid.start + (row + 0.5 + jitter_ * (uniform (key, 2 * static_cast<std::uint64_t> (cell) + 1) - 0.5)) * grid.cell;
              std::int32_t index = -1;
              double w = state;
              if (state < 0.0f)
              {
                HeightSample h;
                w = placeWeight (p, x, y, h, true);
                if (w == 0.0)
                  continue;
                if (store)
                {
                  index = static_cast<std::int32_t> (evaluated.size ());
                  evaluated.emplace_back ();
                  makePoint (p, x, y, h, evaluated.back ());
                }
              }
              if (store)
                out.push_back ({static_cast<float> (x), static_cast<float> (y), static_cast<float> (w), cell, index});
              ++count;
              sum += w;
            }
        }
        if (kept)
          *kept = count;
        return sum;
      }

      /// Where the systematic sampling of one patch's candidates stands between two points: a patch's
      /// selection can stop after any point and resume (blocks of a streamed compute) with the same
      /// arithmetic as one uninterrupted run.
      struct Cursor
      {
        std::size_t k = 0;        ///< current candidate
        int draw = 0;             ///< points already drawn in candidate k
        double t = 0.0;           ///< position of the next point along the cumulative weight
        double cumulative = 0.0;  ///< cumulative weight before candidate k
        double step = 0.0;        ///< weight between two points
        std::size_t emitted = 0;  ///< points of the patch emitted (or skipped) so far
      };

      /// The cursor before the first of \a count points of \a candidates.
      static Cursor
      startSelection (std::uint64_t key, const std::vector<Candidate>& candidates, std::size_t count)
      {
        Cursor cursor;
        double total = 0.0;
        for (const Candidate& c : candidates)
          total += c.weight;
        cursor.step = total / static_cast<double> (count);
        cursor.t = uniform (key, ~0ULL) * cursor.step;
        return cursor;
      }

      /// Moves \a cursor on to point \a limit, calling \a visit (candidate, draw, point) for each point.
      template <typename Visit>
      static void
      advance (Cursor& cursor, const std::vector<Candidate>& candidates, std::size_t limit, Visit&& visit)
      {
        while (cursor.k < candidates.size () && cursor.emitted < limit)
        {
          const Candidate& c = candidates[cursor.k];
          const double high = (cursor.k + 1 == candidates.size ()) ? std::numeric_limits<double>::infinity ()
                                                                   : cursor.cumulative + c.weight;
          for (; cursor.t < high && cursor.emitted < limit; ++cursor.draw, cursor.t += cursor.step)
            visit (c, cursor.draw, cursor.emitted++);
          if (cursor.emitted >= limit)
            return;  // resumes in the same candidate: t tells whether it has more points
          cursor.cumulative = high;
          ++cursor.k;
          cursor.draw = 0;
        }
      }

      /// Skips to point \a limit of the patch without making points (no evaluation).
      static void
      skip (Cursor& cursor, const std::vector<Candidate>& candidates, std::size_t limit)
      {
        advance (cursor, candidates, limit, [] (const Candidate&, int, std::size_t) {});
      }

      /// Points \a cursor.emitted .. \a limit - 1 of patch \a p from \a candidates by systematic sampling of
      /// their cumulative weight, into \a out (which receives point \a cursor.emitted first). With \a
      /// attributes (optional), also each point's attribute channels, C per point.
      void
      selectPoints (std::size_t p, const PatchGrid& grid, std::uint64_t key, const std::vector<Candidate>& candidates,
                    const Points& evaluated, Cursor& cursor, std::size_t limit, pcl::PointNormal* out,
                    float* attributes) const
      {
        if (candidates.empty ())
          return;
        const std::uint64_t cells = static_cast<std::uint64_t> (grid.n) * grid.n;
        const std::size_t first = cursor.emitted;
        // The first point of a cell not yet evaluated (most points) waits in a block of places evaluated
        // together; the others (evaluated with the candidate, or redrawn in the cell) are made at once.
        PointBlock block;
        advance (cursor, candidates, limit, [&] (const Candidate& c, int draw, std::size_t point) {
          const std::size_t i = point - first;
          Eigen::Vector2d xy (c.x, c.y);
          if (draw == 0 && c.evaluated >= 0)
            out[i] = evaluated[c.evaluated];
          else if (draw == 0)
            block.add (*this, p, xy.x (), xy.y (), out + i);
          else
            xy = emit (p, grid, key, c, draw, cells, out[i]);
          if (attributes)
            attributesAt (p, xy, attributes + i * model_.attribute_channels.size ());
        });
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
          const int row = static_cast<int> (c.cell / static_cast<std::uint32_t> (grid.n));
          const int col = static_cast<int> (c.cell % static_cast<std::uint32_t> (grid.n));
          // Anywhere in the cell first; then, where the patch keeps only a sliver of the cell (a steep
          // border: its candidate weighs up to max_area_weight cells), places drawn ever nearer the
          // candidate. Where none is kept (a cell taken whole from its corners whose candidate lies in a
          // gap), the point moves 1/64 of the cell off the candidate on its code all the same: falling back
          // on the candidate itself wrote the same point twice (blade -n 32924: 6 pairs, koala: 3).
          const int fresh = 8, attempts = 24;
          for (int attempt = 0; attempt < attempts && !found; ++attempt)
          {
            const std::uint64_t drawn = static_cast<std::uint64_t> (attempt % fresh);
            const std::uint64_t index = 2 * (cells * (fresh * static_cast<std::uint64_t> (draw) + drawn) + c.cell);
            const double xa = grid.start + (col + uniform (key, index)) * grid.cell;
            const double ya = grid.start + (row + uniform (key, index + 1)) * grid.cell;
            const double shrink = attempt < fresh ? 1.0 : attempt + 1 < attempts ? std::ldexp (1.0, fresh - 1 - attempt) : 1.0 / 64.0;
            x = c.x + shrink * (xa - c.x);
            y = c.y + shrink * (ya - c.y);
            found = placeWeight (p, x, y, h) > 0.0;
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

    /// cloud.resize (n) as PCL's (width n, height 1), with the points on huge pages (common/huge_pages.h).
    template <typename Cloud>
    void
    resizeCloudOnHugePages (Cloud& cloud, std::size_t n)
    {
      resizeOnHugePages (cloud.points, n);
      cloud.width = static_cast<std::uint32_t> (n);
      cloud.height = 1;
    }
  } // namespace

  /// The tables and per-patch results the passes share.
  struct SparseSurfaceResamplingBase::Passes
  {
    Passes (const PatchEvaluator& evaluator, const PatchOwnership& ownership, const SparseSurfaceResamplingOptions& options,
            std::size_t m)
      : sampler (evaluator, ownership, options.jitter, options.max_area_weight), candidates (m), evaluated (m),
        weights (m, 0.0), sizes (m, 0), grids (m), kept (m, 0)
    {}

    const PatchSampler sampler;
    std::vector<std::vector<Candidate>> candidates;
    std::vector<Points> evaluated;
    std::vector<double> weights;
    std::vector<std::size_t> sizes;  ///< number of candidates of each patch
    std::vector<PatchGrid> grids;
    std::vector<std::uint8_t> kept;  ///< whether candidates[p] holds the patch's candidates
  };

  /// What one block of a streamed compute does: the pieces of patches it holds, each cut into spans
  /// the threads share, with where each span's selection starts.
  struct SparseSurfaceResamplingBase::BlockPlan
  {
    struct Span
    {
      std::size_t patch;
      PatchSampler::Cursor cursor;  ///< at the span's first point
      std::size_t limit;            ///< the point of the patch after its last
      std::size_t out;              ///< position of its first point in the block
      bool closes;                  ///< the last span of the block's piece of this patch
    };
    std::vector<Span> spans;
    /// Span-index range of each patch of the block, in patch order.
    std::vector<std::pair<std::size_t, std::size_t>> patches;
    /// Where each unfinished patch's selection stands after the previous block (by patch).
    std::vector<PatchSampler::Cursor> cursors;
  };

  void
  SparseSurfaceResamplingOptions::validate () const
  {
    auto fail = [] (const std::string& field, double value, const std::string& range) {
      throwOutOfRange ("SparseSurfaceResamplingOptions", field, value, range);
    };
    if (!(jitter >= 0.0 && jitter <= 1.0))
      fail ("jitter", jitter, "0 <= jitter <= 1");
    if (!(max_area_weight >= 1.0) || !std::isfinite (max_area_weight))
      fail ("max_area_weight", max_area_weight, "max_area_weight >= 1, finite");
    if (area_pass_cells < 1)
      fail ("area_pass_cells", area_pass_cells, "area_pass_cells >= 1");
    ownership.validate ();
  }

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
      throw Error ("[" + name_ + "::setPointCount] point count must be in [1, " + std::to_string (max_points) + "], got " +
                   std::to_string (count));
    mode_ = Mode::Count;
    count_ = count;
  }

  void
  SparseSurfaceResamplingBase::setDensity (double density)
  {
    if (!(density > 0.0) || !std::isfinite (density))
      throw Error ("[" + name_ + "::setDensity] density must be a positive number of points per unit area, got " +
                   shortestDecimal (density));
    mode_ = Mode::Density;
    density_ = density;
  }

  void
  SparseSurfaceResamplingBase::setSpacing (double spacing)
  {
    if (!(spacing > 0.0) || !std::isfinite (spacing))
      throw Error ("[" + name_ + "::setSpacing] spacing must be a positive length, got " + shortestDecimal (spacing));
    // 1e-200 gave an infinite density, 1e200 a zero one, and the error named a density nobody set.
    const double density = 1.0 / (spacing * spacing);
    if (!(density > 0.0) || !std::isfinite (density))
    {
      std::ostringstream message;
      message << name_ << ": spacing " << spacing << " gives no usable density (1 / spacing^2 must be a finite number > 0)";
      throw Error (message.str ());
    }
    setDensity (density);
  }

  void
  SparseSurfaceResamplingBase::resample (PointCloud& output, bool with_attributes)
  {
    with_attributes_ = with_attributes;
    checkSetup ();
    computeResampling (output);
  }

  void
  SparseSurfaceResamplingBase::resampleBlocks (const std::function<void (const ResampledBlock<pcl::PointNormal>&)>& callback,
                                               bool with_attributes)
  {
    with_attributes_ = with_attributes;
    checkSetup ();
    point_patches_.clear ();
    point_attributes_.clear ();
    prepareTables ();
    Passes passes (*evaluator_, *ownership_, options_, model_->numPatches ());
    weighPatches (passes, nullptr, stream_.kept_candidate_bytes);
    streamAllPoints (pointsPerPatch (passes.weights), passes, callback);
    if (progress_)
      progress_ ("resample", 1.0);
  }

  void
  SparseSurfaceResamplingBase::checkSetup () const
  {
    if (!model_)
      throw Error ("[" + name_ + "::compute] no input model (setInputModel)");
    if (!model_->basis)
      throw Error ("[" + name_ + "::compute] the model has no basis");
    if (model_->patches.empty ())
      throw Error ("[" + name_ + "::compute] the model has no patches");
    if (mode_ == Mode::None)
      throw Error ("[" + name_ + "::compute] no density given (setPointCount, setDensity or setSpacing)");
    options_.validate ();
    // A model from a file was checked by its reader; one built in memory is checked here (a NaN seed
    // aborted in the kd-tree, an atom outside the basis wrote past the evaluator's tables).
    model_->checkPatches ("[" + name_ + "::compute] ");
    for (const PatchCode& code : model_->patches)
      if (!(code.origin.cwiseAbs ().maxCoeff () < max_coordinate && code.radius < max_coordinate))
        throw Error ("[" + name_ + "::compute] a patch lies beyond the range of float coordinates (1e30)");
    if (!patch_numbers_.empty () && patch_numbers_.size () != model_->patches.size ())
      throw Error ("[" + name_ + "::compute] " + std::to_string (patch_numbers_.size ()) + " patch numbers for " +
                   std::to_string (model_->patches.size ()) + " patches");
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
    ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 8) num_threads(threadsToUse ())
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
      failure.run ([&] {
        const std::size_t p = static_cast<std::size_t> (pi);
        const double e = evaluator_->maxExtent (p);
        const double final_cell = 1.0 / (model.patches[p].radius * std::sqrt (guess));
        const PatchGrid grid = makeGrid (e, std::min (e, std::max (2.0 * e / cells_per_axis, 2.0 * final_cell)));
        std::vector<Candidate> candidates;
        Points evaluated;
        const double r = model.patches[p].radius;
        areas[p] = sampler.drawCandidates (p, grid, patchKey (options_.seed, patchNumber (p), 0), candidates, evaluated, false) *
                   grid.cell * grid.cell * r * r;
      });
    failure.rethrow ();
    const double area = std::accumulate (areas.begin (), areas.end (), 0.0);
    if (!(area > 0.0))
      throw Error ("[" + name_ + "::compute] the model has no surface area to sample");
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
  SparseSurfaceResamplingBase::drawAllCandidates (double& density, Passes& passes, PointCloud* prefill,
                                                  std::size_t keep_bytes) const
  {
    // Every patch's kept places and owned area at the final density. With a total count, cells hold one
    // point each only if the area pass was right: if the measured area differs by more than 2%, the pass
    // is redone once at the corrected density (systematic sampling at a step off by x% skips or doubles
    // every (100/x)-th cell, which shows in the spacing). A count so small that no cell keeps a candidate
    // also retries, at 4 x the density.
    const std::size_t m = model_->numPatches ();
    const int threads = threadsToUse ();
    std::atomic<std::size_t> done (0), kept_bytes (0);
    for (int attempt = 0, corrections = 0; attempt < 16; ++attempt)
    {
      done = 0;
      kept_bytes = 0;
      ParallelFailure failure;
#pragma omp parallel num_threads(threads)
      {
#pragma omp single nowait
        if (prefill && attempt == 0)
          failure.run ([&] {
            prefill->clear ();
            resizeCloudOnHugePages (*prefill, count_);
          });
#pragma omp for schedule(dynamic, 4)
        for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
          failure.run ([&] {
            const std::size_t p = static_cast<std::size_t> (pi);
            const double r = model_->patches[p].radius;
            passes.grids[p] = makeGrid (evaluator_->maxExtent (p), 1.0 / (r * std::sqrt (density)));
            // Which patches keep their candidates depends on the threads' timing, the points do not: a
            // patch not kept only sums its weights now, and draws the same candidates from the same hashes
            // in its block.
            // A patch whose grid alone could take a quarter of the budget is not even drawn for keeping.
            const std::size_t cells = static_cast<std::size_t> (passes.grids[p].n) * passes.grids[p].n;
            const bool store = kept_bytes.load () < keep_bytes && cells <= keep_bytes / 4 / sizeof (Candidate);
            passes.weights[p] = passes.sampler.drawCandidates (p, passes.grids[p], patchKey (options_.seed, patchNumber (p), 1),
                                                              passes.candidates[p], passes.evaluated[p], store,
                                                              &passes.sizes[p]) *
                                passes.grids[p].weight;
            const std::size_t bytes = passes.candidates[p].capacity () * sizeof (Candidate) +
                                      passes.evaluated[p].capacity () * sizeof (pcl::PointNormal);
            passes.kept[p] = store && kept_bytes.fetch_add (bytes) + bytes <= keep_bytes;
            if (store && !passes.kept[p])
            {
              kept_bytes -= bytes;
              std::vector<Candidate> ().swap (passes.candidates[p]);
              Points ().swap (passes.evaluated[p]);
            }
            const std::size_t finished = ++done;
            if (progress_ && omp_get_thread_num () == 0)
              progress_ ("resample", 0.5 * static_cast<double> (finished) / static_cast<double> (m));
          });
      }
      failure.rethrow ();
      if (mode_ != Mode::Count)
        break;
      const double expected = std::accumulate (passes.weights.begin (), passes.weights.end (), 0.0);
      if (!(expected > 0.0))
      {
        // Where the area pass found only slivers no candidate keeps (a doubly covered flat disk, each side
        // owning nothing against the other), each retry quadruples the cells: stop while they are few.
        std::size_t cells = 0;
        for (const PatchGrid& grid : passes.grids)
          cells += static_cast<std::size_t> (grid.n) * static_cast<std::size_t> (grid.n);
        if (cells > 64 * (count_ + m))
          throw Error ("[" + name_ + "::compute] the model has no surface area to sample (no place of it is kept)");
        density *= 4.0;
        continue;
      }
      const double ratio = static_cast<double> (count_) / expected;
      if (std::abs (ratio - 1.0) <= 0.02 || corrections++ > 0)
        break;
      density *= ratio;
    }
    // Halfway, from the calling thread: the reports inside the loop come from thread 0 alone, which may
    // have drawn no patch when the other threads took them all (a test's cancellation was then never seen).
    if (progress_)
      progress_ ("resample", 0.5);
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
      throw Error ("[" + name_ + "::compute] density gives more than " + std::to_string (max_points) + " points");
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
      resizeCloudOnHugePages (output, offsets[m]);
    }
    point_patches_.clear ();
    resizeOnHugePages (point_patches_, offsets[m]);
    const std::size_t channels = with_attributes_ ? model_->attribute_channels.size () : 0;
    point_attributes_.clear ();
    resizeOnHugePages (point_attributes_, offsets[m] * channels);
    std::atomic<std::size_t> done (0);
    ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 4) num_threads(threadsToUse ())
    for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t> (m); ++pi)
      failure.run ([&] {
        const std::size_t p = static_cast<std::size_t> (pi);
        if (counts[p] > 0)
        {
          const std::uint64_t key = patchKey (options_.seed, patchNumber (p), 3);
          PatchSampler::Cursor cursor = PatchSampler::startSelection (key, passes.candidates[p], counts[p]);
          passes.sampler.selectPoints (p, passes.grids[p], key, passes.candidates[p], passes.evaluated[p], cursor, counts[p],
                                       output.data () + offsets[p],
                                       channels > 0 ? point_attributes_.data () + offsets[p] * channels : nullptr);
        }
        std::fill (point_patches_.begin () + offsets[p], point_patches_.begin () + offsets[p + 1], static_cast<int> (p));
        std::vector<Candidate> ().swap (passes.candidates[p]);
        Points ().swap (passes.evaluated[p]);
        const std::size_t finished = ++done;
        if (progress_ && omp_get_thread_num () == 0)
          progress_ ("resample", 0.5 + 0.5 * static_cast<double> (finished) / static_cast<double> (m));
      });
    failure.rethrow ();
    output.width = static_cast<std::uint32_t> (output.size ());
    output.height = 1;
    output.is_dense = true;
  }

  void
  SparseSurfaceResamplingBase::streamAllPoints (const std::vector<std::size_t>& counts, Passes& passes,
                                                const std::function<void (const ResampledBlock<pcl::PointNormal>&)>& callback)
  {
    const std::size_t m = counts.size ();
    std::vector<std::size_t> offsets (m + 1, 0);
    for (std::size_t p = 0; p < m; ++p)
      offsets[p + 1] = offsets[p] + counts[p];
    const std::size_t total = offsets[m];
    const std::size_t block_points = std::max<std::size_t> (1, stream_.block_points);
    const std::size_t channels = with_attributes_ ? model_->attribute_channels.size () : 0;
    ResampledBlock<pcl::PointNormal> block;
    block.total = total;
    BlockPlan plan;
    plan.cursors.resize (m);
    std::size_t begin = 0;
    do
    {
      const std::size_t end = std::min (total, begin + block_points);
      planBlock (offsets, begin, end, passes, plan);
      // Every point of the block is written below, as in selectAllPoints.
      resizeCloudOnHugePages (block.cloud, end - begin);
      resizeOnHugePages (block.patches, end - begin);
      resizeOnHugePages (block.attributes, (end - begin) * channels);
      ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threadsToUse ())
      for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t> (plan.spans.size ()); ++k)
        failure.run ([&] {
          BlockPlan::Span& span = plan.spans[static_cast<std::size_t> (k)];
          const std::size_t p = span.patch, first = span.out, size = span.limit - span.cursor.emitted;
          passes.sampler.selectPoints (p, passes.grids[p], patchKey (options_.seed, patchNumber (p), 3), passes.candidates[p],
                                       passes.evaluated[p], span.cursor, span.limit, block.cloud.data () + first,
                                       channels > 0 ? block.attributes.data () + first * channels : nullptr);
          std::fill (block.patches.begin () + first, block.patches.begin () + first + size, static_cast<int> (p));
          if (span.closes)
            plan.cursors[p] = span.cursor;
        });
      failure.rethrow ();
      // A patch finished in this block frees its candidates; one cut by the block's end keeps them.
      for (const auto& range : plan.patches)
      {
        const std::size_t p = plan.spans[range.first].patch;
        if (offsets[p + 1] <= end)
        {
          std::vector<Candidate> ().swap (passes.candidates[p]);
          Points ().swap (passes.evaluated[p]);
          passes.kept[p] = 0;
        }
      }
      block.cloud.width = static_cast<std::uint32_t> (block.cloud.size ());
      block.cloud.height = 1;
      block.cloud.is_dense = true;
      block.first = begin;
      callback (block);
      if (progress_ && total > 0)
        progress_ ("resample", 0.5 + 0.5 * static_cast<double> (end) / static_cast<double> (total));
      begin = end;
    } while (begin < total);
  }

  void
  SparseSurfaceResamplingBase::planBlock (const std::vector<std::size_t>& offsets, std::size_t begin, std::size_t end,
                                          Passes& passes, BlockPlan& plan) const
  {
    // Spans of at most 32768 points: enough for two threads to share a block held by one large patch.
    constexpr std::size_t span_points = 32768;
    const std::size_t m = offsets.size () - 1;
    plan.spans.clear ();
    plan.patches.clear ();
    std::size_t p = static_cast<std::size_t> (std::upper_bound (offsets.begin (), offsets.end (), begin) - offsets.begin ()) - 1;
    for (; p < m && offsets[p] < end; ++p)
    {
      const std::size_t from = std::max (begin, offsets[p]) - offsets[p], to = std::min (end, offsets[p + 1]) - offsets[p];
      if (from == to)
        continue;
      const std::size_t first_span = plan.spans.size ();
      for (std::size_t a = from; a < to; a += span_points)
      {
        const std::size_t b = std::min (to, a + span_points);
        plan.spans.push_back ({p, PatchSampler::Cursor (), b, offsets[p] + a - begin, b == to});
      }
      plan.patches.emplace_back (first_span, plan.spans.size ());
    }
    // Each patch: its candidates unless kept from the weight pass, then the cursor at each span's start
    // (skipping is cheap: no evaluation), in parallel over the patches.
    ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threadsToUse ())
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t> (plan.patches.size ()); ++k)
      failure.run ([&] {
        const auto [s0, s1] = plan.patches[static_cast<std::size_t> (k)];
        const std::size_t q = plan.spans[s0].patch;
        if (!passes.kept[q])
        {
          passes.sampler.drawCandidates (q, passes.grids[q], patchKey (options_.seed, patchNumber (q), 1), passes.candidates[q],
                                         passes.evaluated[q], true, nullptr, passes.sizes[q]);
          passes.kept[q] = 1;
        }
        PatchSampler::Cursor cursor = offsets[q] >= begin
                                        ? PatchSampler::startSelection (patchKey (options_.seed, patchNumber (q), 3), passes.candidates[q],
                                                                        offsets[q + 1] - offsets[q])
                                        : plan.cursors[q];
        for (std::size_t span = s0; span < s1; ++span)
        {
          if (span > s0)
            PatchSampler::skip (cursor, passes.candidates[q], plan.spans[span - 1].limit);
          plan.spans[span].cursor = cursor;
        }
      });
    failure.rethrow ();
  }

  void
  SparseSurfaceResamplingBase::prepareTables ()
  {
    if (!evaluator_)
      evaluator_ = std::make_shared<PatchEvaluator> (*model_);
    if (!ownership_)
      ownership_ = std::make_shared<PatchOwnership> (*evaluator_, options_.ownership, threadsToUse ());
  }

  void
  SparseSurfaceResamplingBase::weighPatches (Passes& passes, PointCloud* prefill, std::size_t keep_bytes)
  {
    // Density: given, or from a coarse area pass when a total count is asked for.
    double density = mode_ == Mode::Count ? densityForCount () : density_;
    checkDensityBound (density);
    drawAllCandidates (density, passes, prefill, keep_bytes);
    const double weight = std::accumulate (passes.weights.begin (), passes.weights.end (), 0.0);
    // weight is the expected number of points: under half a point, the cloud would be empty or one lucky point.
    if (!(weight >= 0.5))
      throw Error ("[" + name_ + "::compute] no point falls on the model's surface at density " + shortestDecimal (density) +
                   " points per unit area (" + shortestDecimal (weight) +
                   " expected: too low for the model's size: raise the density or ask for a count)");
    // A cell holds one expected point on flat ground, so weights are areas in units of 1 / density.
    estimated_area_ = weight / density;
    density_used_ = density;
  }

  void
  SparseSurfaceResamplingBase::checkCloudFitsInMemory (double points) const
  {
    const double bytes_per_point = 90.0;  // decode -n 2M / 8M -stream off: 190 / 723 MB peak
    std::ostringstream what;
    what.precision (3);
    what << name_ << "::compute: " << points << " points held in memory";
    checkFitsInMemory (points * bytes_per_point, what.str (), "lower the count or density, or resample in blocks");
  }

  void
  SparseSurfaceResamplingBase::computeResampling (PointCloud& output)
  {
    prepareTables ();
    Passes passes (*evaluator_, *ownership_, options_, model_->numPatches ());
    // With a count, the cloud's size is known: its construction overlaps the candidate pass.
    const bool prefill = mode_ == Mode::Count;
    if (prefill)
      checkCloudFitsInMemory (static_cast<double> (count_));
    weighPatches (passes, prefill ? &output : nullptr, std::numeric_limits<std::size_t>::max ());
    if (!prefill)
      checkCloudFitsInMemory (std::accumulate (passes.weights.begin (), passes.weights.end (), 0.0));
    selectAllPoints (pointsPerPatch (passes.weights), passes, output, prefill);
    if (progress_)
      progress_ ("resample", 1.0);
  }

#define PCL_SPARSE_INSTANTIATE_RESAMPLING(T) template class SparseSurfaceResampling<T>;
  PCL_SPARSE_FOR_EACH_OUTPUT_POINT_TYPE (PCL_SPARSE_INSTANTIATE_RESAMPLING)
#undef PCL_SPARSE_INSTANTIATE_RESAMPLING
} // namespace pcl_sparse
