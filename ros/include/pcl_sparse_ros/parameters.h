#pragma once
/// \file parameters.h
/// The ROS parameters of the nodes and nodelets, read once at start-up from the private namespace.
/// Anything out of range throws pcl_sparse::Error naming the parameter (the node exits, the nodelet
/// logs it and stays idle).

#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <ros/node_handle.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>

namespace pcl_sparse_ros
{
  /// How many points a resampling gives: `~points` (exact count), `~density` (points per square unit of
  /// the frame, usually m^2) or `~spacing` (mean distance between neighbours); at most one of them.
  struct PointBudget
  {
    enum class Kind { Default, Points, Density, Spacing };
    Kind kind = Kind::Default;  ///< Default: the count the caller passes to apply()
    double value = 0.0;

    /// Sets the budget on \a resampling; \a default_count is used for Kind::Default.
    void apply (pcl_sparse::SparseSurfaceResamplingBase& resampling, std::size_t default_count) const;
    /// "points 5000", "density 4e+04 /m^2", "spacing 0.005", or "default".
    std::string describe () const;
  };

  /// Reads ~points, ~density and ~spacing from \a private_nh.
  PointBudget
  readPointBudget (const ros::NodeHandle& private_nh);

  /// How the nodes resample: the point budget and the library's resampling options.
  struct ResamplingSettings
  {
    PointBudget budget;
    /// The library's defaults, with ~max_slope (degrees, in (0, 90]) as ownership.max_slope_angle: a patch
    /// leaves places it sees more steeply to the patch that sees them frontally (pcl_sparse_resample
    /// -max-slope); and ~clearance (>= 0) as ownership.opposite_clearance: places that close to the other
    /// side of a knife edge stay unsampled (-clearance).
    pcl_sparse::SparseSurfaceResamplingOptions options;

    /// Sets the options and the budget on \a resampling (\a default_count for PointBudget::Kind::Default).
    void apply (pcl_sparse::SparseSurfaceResamplingBase& resampling, std::size_t default_count) const;
    /// The budget's description, the slope bound and the clearance: "points 5000, max slope 50, clearance 0.03".
    std::string describe () const;
  };

  /// Reads ~points, ~density, ~spacing, ~max_slope and ~clearance from \a private_nh.
  ResamplingSettings
  readResamplingSettings (const ros::NodeHandle& private_nh);

  /// What the resample node passes to the encoder and the model writer.
  struct EncoderSettings
  {
    std::string preset = "default";                  ///< ~preset
    pcl_sparse::SparseSurfaceEncoderOptions options; ///< the preset's options, then ~rho
    bool has_viewpoint = false;                      ///< ~viewpoint given: the sensor position normals face
    Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero ();  ///< (SparseSurfaceEncoder::setViewPoint)
    double model_tolerance = 1e-4;                   ///< ~model_tolerance: .psm tolerance (fraction of bbox diagonal; 0 = lossless)
    int threads = 0;                                 ///< ~threads: OpenMP threads (0 = all); outputs do not depend on it
  };

  /// Reads ~preset, ~rho, ~viewpoint, ~model_tolerance and ~threads from \a private_nh.
  EncoderSettings
  readEncoderSettings (const ros::NodeHandle& private_nh);

  /// \brief The encoder options of a named preset (pcl_sparse::encoderPresetOptions): "default" (the
  /// library's defaults, the quadric and dct atoms) or "paper" (the paper's configuration). Throws for other names.
  pcl_sparse::SparseSurfaceEncoderOptions
  presetOptions (const std::string& preset);

  /// Reads ~threads (0 = all): a whole number in [0, 1024].
  int
  readThreads (const ros::NodeHandle& private_nh);

  /// Reads the string parameter ~\a name, \a fallback when it is not set. Throws pcl_sparse::Error when it
  /// is set to something else (roscpp's param () silently took the fallback: _preset:=5 ran the default).
  std::string
  readString (const ros::NodeHandle& private_nh, const std::string& name, const std::string& fallback);
} // namespace pcl_sparse_ros
