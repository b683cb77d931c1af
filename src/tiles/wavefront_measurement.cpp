#include <pcl_sparse/tiles/wavefront_measurement.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/tiles/tile_encoding.h>

#include <algorithm>
#include <chrono>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace pcl_sparse
{
  int
  wavefrontAxis (const TileGrid& grid)
  {
    int axis = 2;
    for (int a = 1; a >= 0; --a)
      if (grid.counts[a] > grid.counts[axis])
        axis = a;
    return axis;
  }

  std::vector<std::size_t>
  wavefrontMeasuringOrder (const TileGrid& grid, const std::vector<std::size_t>& core)
  {
    const int axis = wavefrontAxis (grid);
    std::vector<std::size_t> order;
    for (std::size_t t = 0; t < grid.size (); ++t)
      if (core[t] > 0)
        order.push_back (t);
    std::stable_sort (order.begin (), order.end (), [&] (std::size_t a, std::size_t b) {
      return grid.coordinates (a)[axis] < grid.coordinates (b)[axis];
    });
    return order;
  }

  namespace
  {
    /// Vertex listings of a tile's patches.
    std::size_t
    listings (const TileEncoding& tile)
    {
      std::size_t n = 0;
      for (const PatchCode& patch : tile.model.patches)
        n += patch.vertices.size ();
      return n;
    }
  } // namespace

  WavefrontMeasurement::WavefrontMeasurement (const TileSource& source, bool drop_vertices)
    : source_ (source), drop_ (drop_vertices)
  {
    const TileGrid& grid = source.grid ();
    const std::size_t n = grid.size ();
    std::vector<std::size_t> core (n);
    for (std::size_t t = 0; t < n; ++t)
      core[t] = source.corePoints (t);
    order_ = wavefrontMeasuringOrder (grid, core);
    // The tiles in the order their errors are added (ascending, as tiledModelStatistics adds them: the same bits).
    for (std::size_t t = 0; t < n; ++t)
      if (core[t] > 0)
        ascending_.push_back (t);
    tiles_.resize (n);
    in_.assign (n, 0);
    held_.assign (n, 0);
    pending_.resize (n);
    widen (1);
  }

  void
  WavefrontMeasurement::widen (int reach)
  {
    if (std::find (in_.begin (), in_.end (), 1) != in_.end ())
      throw Error ("WavefrontMeasurement::widen: tiles are already in");
    // The tiles with core points around each tile; the last tile measured that needs each tile's patches
    // (their vertex lists can go after it), as a position in order_.
    const TileGrid& grid = source_.grid ();
    std::vector<char> has_core (grid.size (), 0);
    for (const std::size_t t : ascending_)
      has_core[t] = 1;
    near_.assign (grid.size (), {});
    last_use_.assign (grid.size (), 0);
    for (std::size_t m = 0; m < order_.size (); ++m)
      for (const std::size_t u : neighbourTiles (grid, order_[m], reach))
        if (has_core[u])
        {
          near_[order_[m]].push_back (u);
          last_use_[u] = m;
        }
  }

  void
  WavefrontMeasurement::addAll (std::vector<TileEncoding> tiles)
  {
    widen (farthestReach (tiles));
    for (TileEncoding& tile : tiles)
      add (std::move (tile));
  }

  void
  WavefrontMeasurement::add (TileEncoding tile)
  {
    const std::size_t t = tile.tile;
    held_[t] = listings (tile);
    if (held_[t] > 0)
    {
      ++held_tiles_;
      held_vertices_ += held_[t];
      peak_held_tiles_ = std::max (peak_held_tiles_, held_tiles_);
      peak_held_vertices_ = std::max (peak_held_vertices_, held_vertices_);
    }
    tiles_[t] = std::move (tile);
    in_[t] = 1;
  }

  bool
  WavefrontMeasurement::hasAround (std::size_t t, bool phase0_only) const
  {
    for (const std::size_t u : near_[t])
      if ((!phase0_only || tilePhase (source_.grid (), u) == 0) && !in_[u])
        return false;
    return true;
  }

  bool
  WavefrontMeasurement::next (std::size_t& t, std::vector<TilePatches>& near) const
  {
    if (next_ >= order_.size () || !hasAround (order_[next_], false))
      return false;
    t = order_[next_];
    near.clear ();
    for (const std::size_t u : near_[t])
      if (!tiles_[u].model.patches.empty ())
        near.push_back ({tiles_[u].model.patches.data (), tiles_[u].model.patches.size (), tiles_[u].model.basis.get (),
                         &tiles_[u].moved});
    return true;
  }

  void
  WavefrontMeasurement::finish (const TileErrors& errors, double seconds)
  {
    const std::size_t t = order_[next_];
    seconds_ += seconds;
    ++pending_tiles_;
    pending_[t] = errors;
    peak_pending_tiles_ = std::max (peak_pending_tiles_, pending_tiles_);
    while (next_add_ < ascending_.size () && pending_[ascending_[next_add_]])
    {
      sums_.add (*pending_[ascending_[next_add_]]);
      pending_[ascending_[next_add_++]].reset ();
      --pending_tiles_;
    }
    if (drop_)
      for (const std::size_t u : near_[t])
        if (last_use_[u] == next_ && held_[u] > 0)
        {
          for (PatchCode& patch : tiles_[u].model.patches)
          {
            std::vector<int> ().swap (patch.vertices);
            std::vector<Eigen::Vector2d> ().swap (patch.vertex_xy);
          }
          tiles_[u].moved = MovedPoints ();
          --held_tiles_;
          held_vertices_ -= held_[u];
          held_[u] = 0;
        }
#if defined(__GLIBC__)
    // Hand freed pages back (the tile's input, the lists just dropped): glibc keeps them in its arenas, and
    // the resident set of a long run crept up while the band held stayed the same size.
    malloc_trim (0);
#endif
    ++next_;
  }

  void
  WavefrontMeasurement::measureReady ()
  {
    std::size_t t = 0;
    std::vector<TilePatches> near;
    while (next (t, near))
    {
      const auto start = std::chrono::steady_clock::now ();
      const TileErrors errors = TiledErrorSums::measureTile (source_, t, near);
      finish (errors, std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ());
    }
  }

  TiledModel
  WavefrontMeasurement::takeModel ()
  {
    std::vector<TileEncoding> tiles;
    for (std::size_t t = 0; t < tiles_.size (); ++t)
      if (in_[t])
        tiles.push_back (std::move (tiles_[t]));
    return mergeTileEncodings (source_.grid (), source_.totalPoints (), std::move (tiles));
  }
} // namespace pcl_sparse
