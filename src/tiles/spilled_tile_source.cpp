#include <pcl_sparse/tiles/spilled_tile_source.h>

#include <pcl_sparse/cloud/depth_quantization.h>
#include <pcl_sparse/cloud/scan_grid.h>
#include <pcl_sparse/cloud/sensor_evidence.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/scan_stream.h>
#include <pcl_sparse/mesh/vertex_welding.h>
#include <pcl_sparse/tiles/tile_membership.h>

#include "spill_files.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace pcl_sparse
{
  struct SpilledTileSource::Impl
  {
    ScanCloud layout;                  ///< the input's fields and sensor pose, no points
    std::optional<tiles_detail::SpillRecord> record;
    ScanCleaningOptions cleaning;
    std::vector<std::size_t> spilled;  ///< records in each tile's file
    /// Runs of points pass 1 dropped (non-finite, at the sensor): first file index of each run, ascending,
    /// and the points dropped before the run's end (prefix sums), for pointNumber.
    std::vector<std::size_t> dropped_from, dropped_through;
    std::vector<std::size_t> duplicates;  ///< file indices of the duplicates cleaning removes, ascending
    std::uint8_t stepped_axes = 0;        ///< the coordinates stored in steps, judged on every kept point

    /// The rank in the cleaned input of the kept point at file index \a index: the index less the points
    /// dropped or merged before it.
    std::size_t
    pointNumber (std::size_t index) const
    {
      const std::size_t runs = static_cast<std::size_t> (std::upper_bound (dropped_from.begin (), dropped_from.end (), index) - dropped_from.begin ());
      const std::size_t dropped = runs == 0 ? 0 : dropped_through[runs - 1];
      const std::size_t merged = static_cast<std::size_t> (std::lower_bound (duplicates.begin (), duplicates.end (), index) - duplicates.begin ());
      return index - dropped - merged;
    }
  };

  namespace
  {
    /// What pass 1 learns: the box and count of the points cleaning does not drop one by one.
    struct FirstPass
    {
      Eigen::AlignedBox3d box;
      ScanCleaningReport report;  ///< input_points, non_finite, at_sensor_origin; kept = the rest
      bool float_vectors = true;  ///< every kept point's vectors are floats: 4-byte coordinates in the spill
      ScanCloud like;             ///< the first chunk's attributes (which ones the file has)
      std::vector<Eigen::Vector3d> sample;       ///< every stride-th kept point (file frame), to judge the pose
      std::optional<SteppedAxes> steps;          ///< every kept point's coordinates, to judge the depth steps
      std::vector<std::size_t> dropped_from;     ///< runs of dropped points: first file index
      std::vector<std::size_t> dropped_through;  ///< points dropped up to the end of each run

      std::size_t next_dropped = 0;              ///< the file index that would extend the last run

      /// Notes that the point at file index \a index (ascending calls) was dropped.
      void
      drop (std::size_t index)
      {
        if (!dropped_from.empty () && index == next_dropped)
          ++dropped_through.back ();
        else
        {
          dropped_from.push_back (index);
          dropped_through.push_back ((dropped_through.empty () ? 0 : dropped_through.back ()) + 1);
        }
        next_dropped = index + 1;
      }
    };

    void
    report (const SpillOptions& options, const char* stage, std::size_t done, std::size_t total)
    {
      if (options.progress)
        options.progress (stage, total == 0 ? 1.0 : static_cast<double> (done) / static_cast<double> (total));
    }

    /// True if cleaning keeps \a p as a single point (it may still be a duplicate); counts it otherwise.
    bool
    keepsPoint (const Eigen::Vector3d& p, const Eigen::Vector3d& sensor, const ScanCleaningOptions& options,
                ScanCleaningReport& report)
    {
      if (!p.allFinite ())
      {
        ++report.non_finite;
        return false;
      }
      if (options.drop_at_sensor_origin && p == sensor)
      {
        ++report.at_sensor_origin;
        return false;
      }
      return true;
    }

    /// defaultPoseIsUnsupported on pass 1's \a sample (file frame, within \a box) of a file of \a layout.
    bool
    sampleDisprovesDefaultPose (const std::vector<Eigen::Vector3d>& sample, const Eigen::AlignedBox3d& box,
                                const ScanCloud& layout)
    {
      if (sample.empty ())
        return false;
      ScanCloud scan;
      scan.origin = box.center ();  // a local frame, as a loaded scan's, so that float spacings keep their digits
      for (const Eigen::Vector3d& p : sample)
        scan.positions.push_back (p - scan.origin);
      scan.width = static_cast<std::uint32_t> (sample.size ());
      scan.height = layout.isOrganized () ? 2 : 1;  // an organized file's pose is a camera's: not judged
      scan.sensor_origin = layout.sensor_origin;
      scan.sensor_orientation = layout.sensor_orientation;
      scan.has_sensor_pose = layout.has_sensor_pose;
      return defaultPoseIsUnsupported (scan, std::vector<std::uint8_t> (sample.size (), 1));
    }

    FirstPass
    firstPass (ScanStreamReader& reader, const SpillOptions& options)
    {
      FirstPass pass;
      // cleanScan compares in the local frame, p == sensor_origin - origin; chunks are in the file's frame.
      const Eigen::Vector3d sensor = cleaningSensorPosition (options.cleaning, reader.layout ().sensor_origin);
      const std::size_t stride = std::max<std::size_t> (1, reader.size () / 4096);
      pass.steps.emplace (reader.size ());
      ScanCloud chunk;
      while (reader.read (chunk, options.chunk_points))
      {
        report (options, "spill: reading", pass.report.input_points, reader.size ());
        if (pass.report.input_points == 0)
        {
          // One point is enough to say which attributes the file has.
          pass.like = chunk;
          for (auto* vectors : {&pass.like.positions, &pass.like.normals, &pass.like.viewpoints})
            vectors->resize (std::min<std::size_t> (vectors->size (), 1));
          pass.like.colors.resize (std::min<std::size_t> (pass.like.colors.size (), 1));
          pass.like.intensities.resize (std::min<std::size_t> (pass.like.intensities.size (), 1));
        }
        const std::size_t first = pass.report.input_points;
        pass.report.input_points += chunk.size ();
        for (std::size_t i = 0; i < chunk.size (); ++i)
          if (keepsPoint (chunk.positions[i], sensor, options.cleaning, pass.report))
          {
            pass.box.extend (chunk.positions[i]);
            pass.steps->add (chunk.positions[i]);
            if ((first + i) % stride == 0)
              pass.sample.push_back (chunk.positions[i]);
            if (i < chunk.intensities.size () && !std::isfinite (chunk.intensities[i]))
              ++pass.report.non_finite_intensities;
            ++pass.report.kept;
            pass.float_vectors = pass.float_vectors && tiles_detail::SpillRecord::isFloat (chunk, i);
          }
          else
            pass.drop (first + i);
      }
      report (options, "spill: reading", 1, 1);
      if (pass.report.kept == 0)
        throw Error (reader.path () + ": " + pass.report.whyNoPointIsLeft ());
      return pass;
    }

    /// Pass 2: every point cleaning keeps one by one, appended to the file of each tile holding it.
    std::vector<std::size_t>
    binPoints (ScanStreamReader& reader, const TileGrid& grid, const tiles_detail::SpillRecord& record,
               const tiles_detail::SpillDirectory& directory, const SpillOptions& options)
    {
      reader.rewind ();
      directory.clear ();
      tiles_detail::SpillWriter writer (directory, grid.size (), record.bytes (), options.buffer_bytes);
      const Eigen::Vector3d sensor = cleaningSensorPosition (options.cleaning, reader.layout ().sensor_origin);
      ScanCleaningReport ignored;
      std::vector<char> bytes (record.bytes ());
      std::vector<std::size_t> tiles;
      ScanCloud chunk;
      std::size_t done = 0;
      while (reader.read (chunk, options.chunk_points))
      {
        report (options, "spill: binning", done, reader.size ());
        done += chunk.size ();
        for (std::size_t i = 0; i < chunk.size (); ++i)
        {
          if (!keepsPoint (chunk.positions[i], sensor, options.cleaning, ignored))
            continue;
          record.encode (chunk, i, bytes.data ());
          tilesHolding (grid, chunk.positions[i], tiles);
          for (const std::size_t t : tiles)
            writer.append (t, bytes.data ());
        }
      }
      writer.flush ();
      report (options, "spill: binning", 1, 1);
      std::vector<std::size_t> spilled (grid.size ());
      for (std::size_t t = 0; t < spilled.size (); ++t)
        spilled[t] = writer.records (t);
      return spilled;
    }

    /// Points each tile owns after merging exact duplicates (all copies of a position own the same tile and
    /// lie in its file), and in \a duplicates the file indices of the copies merging removes (all but the
    /// first in file order, as a scan in memory: a tile's file is in file order), ascending. Reads one tile's
    /// positions at a time.
    std::vector<std::size_t>
    ownedPoints (const TileGrid& grid, const std::vector<std::size_t>& spilled, const tiles_detail::SpillRecord& record,
                 const tiles_detail::SpillDirectory& directory, const SpillOptions& options,
                 std::vector<std::size_t>& duplicates)
    {
      std::vector<std::size_t> owned (grid.size (), 0);
      duplicates.clear ();
      std::vector<Eigen::Vector3d> positions;
      std::vector<std::size_t> file_indices;
      for (std::size_t t = 0; t < grid.size (); ++t)
      {
        report (options, "spill: counting", t, grid.size ());
        positions.clear ();
        file_indices.clear ();
        tiles_detail::readSpillFile (directory.tileFile (t), spilled[t], record.bytes (), [&] (const char* in) {
          const Eigen::Vector3d p = record.position (in);
          if (grid.tileOf (p) != t)
            return;
          positions.push_back (p);
          file_indices.push_back (record.index (in));
        });
        owned[t] = positions.size ();
        if (!options.cleaning.merge_duplicates)
          continue;
        FirstPositionTable first (positions, positions.size ());
        for (std::size_t i = 0; i < positions.size (); ++i)
          if (first.add (positions[i], i) != i)
          {
            duplicates.push_back (file_indices[i]);
            --owned[t];
          }
      }
      std::sort (duplicates.begin (), duplicates.end ());
      report (options, "spill: counting", 1, 1);
      return owned;
    }

    bool
    sameGrid (const TileGrid& a, const TileGrid& b)
    {
      return a.origin == b.origin && a.edge == b.edge && a.counts == b.counts && a.margin == b.margin;
    }
  } // namespace

  SpilledTileSource::SpilledTileSource (const std::string& path, const SpillOptions& options)
  {
    if (options.chunk_points == 0 || options.buffer_bytes == 0)
      throw Error ("SpilledTileSource: chunk_points and buffer_bytes must be positive");
    // Bad grid options are refused before the file is read (makeTileGrid checks them).
    makeTileGrid (Eigen::AlignedBox3d (Eigen::Vector3d::Zero (), Eigen::Vector3d::Ones ()), 1, options.grid);
    ScanStreamReader reader (path);
    directory_ = std::make_unique<tiles_detail::SpillDirectory> (options.directory);
    streamed_ = reader.isStreamed ();

    const FirstPass pass = firstPass (reader, options);
    auto impl = std::make_unique<Impl> ();
    impl->layout = reader.layout ();
    impl->layout.has_sensor_pose = impl->layout.has_sensor_pose && !sampleDisprovesDefaultPose (pass.sample, pass.box, impl->layout);
    impl->record.emplace (pass.like, pass.float_vectors,
                          reader.size () <= static_cast<std::size_t> (std::numeric_limits<std::uint32_t>::max ()));
    impl->cleaning = options.cleaning;
    impl->dropped_from = pass.dropped_from;
    impl->dropped_through = pass.dropped_through;

    // The grid from the count before merging duplicates (all pass 1 knows), then from the true count; the
    // true count does not depend on the grid, so a second binning is the last.
    grid_ = makeTileGrid (pass.box, pass.report.kept, options.grid);
    for (int attempt = 0;; ++attempt)
    {
      impl->spilled = binPoints (reader, grid_, *impl->record, *directory_, options);
      core_points_ = ownedPoints (grid_, impl->spilled, *impl->record, *directory_, options, impl->duplicates);
      report_ = pass.report;
      report_.kept = 0;
      for (const std::size_t n : core_points_)
        report_.kept += n;
      report_.duplicates_merged = pass.report.kept - report_.kept;
      const TileGrid exact = makeTileGrid (pass.box, report_.kept, options.grid);
      if (sameGrid (exact, grid_) || attempt > 0)
        break;
      grid_ = exact;
    }
    impl->stepped_axes = pass.steps->judge (report_.kept);  // duplicates merged, as a scan in memory
    impl_ = std::move (impl);
  }

  SpilledTileSource::~SpilledTileSource () = default;

  std::size_t
  SpilledTileSource::corePoints (std::size_t t) const
  {
    if (t >= core_points_.size ())
      throw Error ("SpilledTileSource::corePoints: tile " + std::to_string (t) + " is not in the grid");
    return core_points_[t];
  }

  std::size_t
  SpilledTileSource::spilledPoints (std::size_t t) const
  {
    if (t >= impl_->spilled.size ())
      throw Error ("SpilledTileSource::spilledPoints: tile " + std::to_string (t) + " is not in the grid");
    return impl_->spilled[t];
  }

  std::size_t
  SpilledTileSource::spilledBytes () const
  {
    std::size_t records = 0;
    for (const std::size_t n : impl_->spilled)
      records += n;
    return records * impl_->record->bytes ();
  }

  const std::string&
  SpilledTileSource::directory () const
  {
    return directory_->path ();
  }

  TileInput
  SpilledTileSource::loadTile (std::size_t t) const
  {
    if (t >= impl_->spilled.size ())
      throw Error ("SpilledTileSource::loadTile: tile " + std::to_string (t) + " is not in the grid");
    TileInput input;
    if (impl_->spilled[t] == 0)
      return input;
    auto scan = std::make_shared<ScanCloud> ();
    const ScanCloud& layout = impl_->layout;
    scan->fields = layout.fields;
    scan->sensor_origin = layout.sensor_origin;
    scan->sensor_orientation = layout.sensor_orientation;
    scan->has_sensor_pose = layout.has_sensor_pose;
    scan->sensor_pose_checked = true;  // on pass 1's sample of the whole file
    scan->stepped_axes = impl_->stepped_axes;
    const std::size_t n = impl_->spilled[t];
    scan->positions.reserve (n);
    scan->indices.reserve (n);
    const tiles_detail::SpillRecord& record = *impl_->record;
    tiles_detail::readSpillFile (directory_->tileFile (t), n, record.bytes (),
                                 [&] (const char* in) { record.decode (in, *scan); });
    scan->width = static_cast<std::uint32_t> (n);
    scan->height = 1;
    cleanScan (*scan, impl_->cleaning);
    scan->width = static_cast<std::uint32_t> (scan->size ());
    // What cleaning removed is the whole input's (cleaningReport); a tile is a cut of the cleaned input.
    scan->report = ScanCleaningReport ();
    scan->report.input_points = scan->report.kept = scan->size ();
    input.point_numbers.resize (scan->size ());
    for (std::size_t i = 0; i < scan->size (); ++i)
      input.point_numbers[i] = impl_->pointNumber (scan->indices[i]);
    if (layout.isOrganized ())  // the file indices are pixels: a camera frame's tile keeps the frame's image grid
      cropToPixelWindow (*scan, layout.width, layout.height);
    centreScan (*scan);
    input.scan = std::move (scan);
    return input;
  }

  SpilledTileSource::Ptr
  spillIntoTiles (const std::string& path, const SpillOptions& options)
  {
    return std::make_shared<SpilledTileSource> (path, options);
  }
} // namespace pcl_sparse
