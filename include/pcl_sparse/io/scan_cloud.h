#pragma once
/// \file scan_cloud.h
/// A scanned point cloud in double precision, in a local frame centred on the data, with what the file
/// said about it (grid shape, sensor pose, attributes) and what cleaning removed.
///
/// Why a local frame: map coordinates (UTM eastings ~5e5 m, northings ~5e6 m) leave float32 a 0.5 m
/// resolution and eat half of double's digits in every difference; centred, every later computation works
/// on small numbers, and origin + p gives the file's coordinates back exactly (see localFrameOrigin).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pcl_sparse
{
  /// What cleaning did to a scan, one count per cause; input_points = non_finite + at_sensor_origin +
  /// duplicates_merged + kept.
  struct ScanCleaningReport
  {
    std::size_t input_points = 0;       ///< points (grid cells for an organized scan) before cleaning
    std::size_t non_finite = 0;         ///< dropped: a NaN/Inf coordinate (also empty grid cells)
    std::size_t at_sensor_origin = 0;   ///< dropped: exactly at the sensor position ("no return" of lidar drivers)
    std::size_t duplicates_merged = 0;  ///< dropped: exactly the position of an earlier kept point
    std::size_t kept = 0;               ///< points left
    /// Kept points whose intensity is NaN or infinite (not dropped: the encoder gives them the nearest point's,
    /// fillAttributeGaps). A spilled scan counts them before exact duplicates are merged.
    std::size_t non_finite_intensities = 0;

    /// Points with finite coordinates (input_points - non_finite).
    std::size_t
    finitePoints () const
    {
      return input_points - non_finite;
    }

    /// "no point left after cleaning (N non-finite, M at the sensor origin)": why a scan is empty, for the
    /// error every reader and stage gives about it.
    std::string
    whyNoPointIsLeft () const
    {
      return "no point left after cleaning (" + std::to_string (non_finite) + " non-finite, " +
             std::to_string (at_sensor_origin) + " at the sensor origin)";
    }

    /// "the scan has no points", and why when cleaning emptied it (a scan built in memory has no report):
    /// the error of a stage given an empty scan.
    std::string
    emptyScanMessage () const
    {
      return "the scan has no points" + (input_points > 0 ? ": " + whyNoPointIsLeft () : std::string ());
    }
  };

  /// A scan: positions in a local frame (world = origin + p) and, where the file has them, per-point normals,
  /// colours and intensities (each either empty or one entry per point).
  struct ScanCloud
  {
    using Ptr = std::shared_ptr<ScanCloud>;
    using ConstPtr = std::shared_ptr<const ScanCloud>;

    std::vector<Eigen::Vector3d> positions;  ///< #P local positions; world position = origin + positions[i]
    Eigen::Vector3d origin = Eigen::Vector3d::Zero ();  ///< the local frame's offset, in the file's frame
    std::vector<Eigen::Vector3d> normals;    ///< empty or #P normals as stored (not normalised)
    std::vector<std::uint32_t> colors;       ///< empty or #P colours packed as PCL's rgba: 0xAARRGGBB
    std::vector<float> intensities;          ///< empty or #P intensities
    /// Empty or #P viewpoints, one per point, in the file's frame (vp_x vp_y vp_z of a merged scan, as
    /// pcl::PointWithViewpoint holds them): each point's normal faces its own sensor.
    std::vector<Eigen::Vector3d> viewpoints;
    /// #P: index of each point in the file, row * width + column for an organized scan (so the grid can be
    /// rebuilt), the position in the file otherwise.
    std::vector<std::size_t> indices;
    /// The file's layout: height > 1 for an organized scan (a range image), else width = #points, height = 1.
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    /// Sensor pose in the file's frame (PCD VIEWPOINT); has_sensor_pose is false when the file states none
    /// (PLY, XYZ), and the sensor is then taken to be at (0, 0, 0).
    Eigen::Vector3d sensor_origin = Eigen::Vector3d::Zero ();
    Eigen::Quaterniond sensor_orientation = Eigen::Quaterniond::Identity ();
    bool has_sensor_pose = false;
    /// The pose was judged on the whole input (a tile's scan, TileSource): defaultPoseIsUnsupported does not
    /// judge it again from the tile's part of the points.
    bool sensor_pose_checked = false;
    /// The coordinates stored in steps, judged on the whole input (a tile's scan, TileSource; SteppedAxes in
    /// depth_quantization.h): a tile's part of a camera frame may be too few points to show its depth
    /// steps. Unset: buildCloudSurface judges the scan's own points.
    std::optional<std::uint8_t> stepped_axes;
    std::vector<std::string> fields;  ///< the point fields of the file (PCD FIELDS, PLY vertex properties), in order
    ScanCleaningReport report;        ///< what cleaning removed (input_points = kept = #P before cleaning)

    std::size_t
    size () const
    {
      return positions.size ();
    }

    bool
    isOrganized () const
    {
      return height > 1;
    }

    /// The position of point \a i in the file's frame: origin + positions[i], in double.
    Eigen::Vector3d
    worldPosition (std::size_t i) const
    {
      return origin + positions[i];
    }
  };

  /// Every position of \a scan in the file's frame (origin + p), in double.
  std::vector<Eigen::Vector3d>
  worldPositions (const ScanCloud& scan);

  /// The origin of the local frame for \a world_positions, per coordinate: 0 where the centre c of the
  /// bounding box of the finite positions is within 2 x its largest side s of 0 (nothing to gain there), else
  /// c rounded to a multiple of the power of two in (s/256, s/128]; the point itself when all coincide, 0 when
  /// there is none. Why so: then p - origin and origin + (p - origin) are exact in double for every finite
  /// position p of the box (far from 0, |p - origin| < |p| and both are multiples of the finer of ulp (p)
  /// and the step), so the local frame loses nothing, for float and double data alike.
  Eigen::Vector3d
  localFrameOrigin (const std::vector<Eigen::Vector3d>& world_positions);
  /// The same for \a box, the bounding box of the finite positions (empty: none).
  Eigen::Vector3d
  localFrameOriginOfBox (const Eigen::AlignedBox3d& box);

  /// Moves \a scan to the local frame of localFrameOrigin (worldPositions (scan)): same world positions,
  /// new origin. Non-finite positions stay non-finite.
  void
  centreScan (ScanCloud& scan);
} // namespace pcl_sparse
