#pragma once
/// \file cloud_resampler.h
/// What pcl_sparse_resample_node and pcl_sparse/ResampleNodelet do: each sensor_msgs/PointCloud2 on
/// ~input is encoded into a sparse surface model (SparseSurfaceEncoder<T> with setInputCloud alone, T
/// chosen from the message's fields), the model is resampled and published on ~output with the input's
/// header, and its .psm bytes on ~model (std_msgs/UInt8MultiArray). Both are latched. A cloud nobody
/// listens to is kept (the last one) and encoded when a subscriber comes: a cloud published once and
/// latched was dropped before anyone listened, and nothing ever came out.
///
/// A cloud the encoder refuses (or a malformed message: cloud_layout.h) is dropped with a throttled
/// ROS_ERROR naming the reason; nothing is published. Shutting down (Ctrl-C) stops an encoding under way.

#include <pcl_sparse_ros/cloud_layout.h>
#include <pcl_sparse_ros/parameters.h>

#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/UInt8MultiArray.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pcl_sparse_ros
{
  /// What one input cloud became.
  struct ResampleResult
  {
    CloudLayout layout;
    /// Resampled, with the input's header (null unless asked). Shared: published as it is, a nodelet in the
    /// same manager gets it without a copy or serialisation.
    sensor_msgs::PointCloud2::Ptr cloud;
    std::vector<std::uint8_t> model;   ///< .psm bytes (empty unless asked)
    std::size_t input_points = 0;      ///< finite input points
    std::size_t kept_points = 0;       ///< points left after the encoder's cleaning (no "no return" zeros, no duplicates)
    std::size_t patches = 0;
    double encode_seconds = 0.0;
    double resample_seconds = 0.0;
    double model_seconds = 0.0;        ///< encodeModel (the .psm bytes)
  };

  /// \brief The node's work on one message, without ROS transport: encode \a input, then resample into
  /// result.cloud if \a want_cloud and write result.model if \a want_model. Throws pcl_sparse::Error when
  /// the cloud has no x y z, the encoder refuses it, or the budget is out of range.
  /// \param[in] resampling point count (PointBudget::Kind::Default = the points the encoder's cleaning
  ///                       keeps, as pcl_sparse_resample on a scan: a clean cloud of the same size) and
  ///                       resampling options
  /// \param[in] on_cloud if set, called with result.cloud as soon as it is made, before the model is
  ///                     written: the node publishes it there, so the model costs the cloud no latency
  ResampleResult
  resampleCloud (const sensor_msgs::PointCloud2& input, const EncoderSettings& settings,
                 const ResamplingSettings& resampling, bool want_cloud, bool want_model,
                 const std::function<void (const sensor_msgs::PointCloud2::ConstPtr&)>& on_cloud = {});

  /// The .psm bytes as a std_msgs/UInt8MultiArray (one dimension labelled "psm").
  std_msgs::UInt8MultiArray
  toModelMessage (std::vector<std::uint8_t>&& bytes);

  /// \brief The ROS side: parameters, ~input, ~output, ~model. Shared by the node and the nodelet.
  class CloudResampler
  {
  public:
    /// Reads the parameters (throws pcl_sparse::Error for bad ones), advertises and subscribes.
    /// \param[in] private_nh the private node handle: parameters and the ~ topics (the node's "~", the
    /// nodelet's getPrivateNodeHandle ())
    explicit CloudResampler (const ros::NodeHandle& private_nh);

  private:
    void onCloud (const sensor_msgs::PointCloud2ConstPtr& input);
    /// Encodes the last input for the outputs that have subscribers and have not had it yet.
    void serveLastInput ();
    /// ROS_ERROR at most every 10 s per instance (each message that fails would otherwise log).
    void errorThrottled (const std::string& message);

    std::string name_;  ///< the private namespace, e.g. /resample: in every log line
    EncoderSettings settings_;
    ResamplingSettings resampling_;
    ros::Publisher cloud_pub_;
    ros::Publisher model_pub_;
    ros::Subscriber sub_;
    sensor_msgs::PointCloud2ConstPtr last_input_;
    bool cloud_served_ = false, model_served_ = false;  ///< the last input's output and model published
    ros::WallTime last_error_;
    std::size_t suppressed_errors_ = 0;
  };
} // namespace pcl_sparse_ros
