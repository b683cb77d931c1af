#pragma once
/// \file model_decoder.h
/// What pcl_sparse_decode_node and pcl_sparse/DecodeNodelet do: the .psm bytes on ~model
/// (std_msgs/UInt8MultiArray, as the resample node publishes them) are decoded and resampled into a
/// PointCloud2 (x y z normal_x normal_y normal_z curvature) on ~output, latched. The bytes carry no
/// header: the cloud gets frame_id ~frame_id and the time it was decoded as its stamp. A model nobody
/// listens to is kept (the last one) and decoded when a subscriber comes.

#include <pcl_sparse_ros/parameters.h>

#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/UInt8MultiArray.h>

#include <string>

namespace pcl_sparse_ros
{
  /// \brief Decodes the .psm bytes of \a model and resamples them (PointBudget::Kind::Default = the model's
  /// number of input points). The header is left empty. Throws pcl_sparse::Error for malformed bytes.
  sensor_msgs::PointCloud2
  decodeModelMessage (const std_msgs::UInt8MultiArray& model, const ResamplingSettings& resampling, int threads);

  /// \brief The ROS side: parameters (~points / ~density / ~spacing, ~max_slope, ~clearance, ~frame_id, ~threads), ~model,
  /// ~output.
  class ModelDecoder
  {
  public:
    /// Reads the parameters (throws pcl_sparse::Error for bad ones), advertises and subscribes.
    explicit ModelDecoder (const ros::NodeHandle& private_nh);

  private:
    void onModel (const std_msgs::UInt8MultiArrayConstPtr& model);
    /// Decodes the last model if ~output has a subscriber and has not had it yet.
    void serveLastModel ();

    std::string name_;
    std::string frame_id_;
    ResamplingSettings resampling_;
    int threads_ = 0;
    ros::Publisher cloud_pub_;
    ros::Subscriber sub_;
    std_msgs::UInt8MultiArrayConstPtr last_model_;
    bool served_ = false;
  };
} // namespace pcl_sparse_ros
