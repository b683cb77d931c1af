#include <pcl_sparse_ros/model_decoder.h>
#include <pcl_sparse_ros/shutdown.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl_conversions/pcl_conversions.h>

#include <boost/make_shared.hpp>

#include <algorithm>
#include <memory>

namespace pcl_sparse_ros
{
  sensor_msgs::PointCloud2
  decodeModelMessage (const std_msgs::UInt8MultiArray& model, const ResamplingSettings& resampling_settings,
                      int threads)
  {
    const auto decoded = std::make_shared<const pcl_sparse::SparseSurfaceModel> (
      pcl_sparse::decodeModel (model.data.data () + model.layout.data_offset,
                               model.data.size () - std::min<std::size_t> (model.layout.data_offset, model.data.size ()),
                               "~model message"));
    pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> resampling;
    resampling.setInputModel (decoded);
    resampling_settings.apply (resampling, decoded->num_input_vertices);
    resampling.setProgressCallback (stopWhenShuttingDown);
    resampling.setNumberOfThreads (threads);
    pcl::PointCloud<pcl::PointNormal> cloud;
    resampling.compute (cloud);
    sensor_msgs::PointCloud2 message;
    pcl::toROSMsg (cloud, message);
    return message;
  }

  ModelDecoder::ModelDecoder (const ros::NodeHandle& private_nh) : name_ (private_nh.getNamespace ())
  {
    ros::NodeHandle nh = private_nh;
    resampling_ = readResamplingSettings (nh);
    threads_ = readThreads (nh);
    frame_id_ = readString (nh, "frame_id", "map");
    const ros::SubscriberStatusCallback on_subscriber = [this] (const ros::SingleSubscriberPublisher&) { serveLastModel (); };
    cloud_pub_ = nh.advertise<sensor_msgs::PointCloud2> ("output", 1, on_subscriber, ros::SubscriberStatusCallback (),
                                                         ros::VoidConstPtr (), true);
    sub_ = nh.subscribe ("model", 1, &ModelDecoder::onModel, this);
    ROS_INFO ("[%s] decoding %s -> %s (%s, frame '%s')", name_.c_str (), sub_.getTopic ().c_str (),
              cloud_pub_.getTopic ().c_str (), resampling_.describe ().c_str (), frame_id_.c_str ());
  }

  void
  ModelDecoder::onModel (const std_msgs::UInt8MultiArrayConstPtr& model)
  {
    last_model_ = model;
    served_ = false;
    serveLastModel ();
  }

  void
  ModelDecoder::serveLastModel ()
  {
    if (served_ || !last_model_ || cloud_pub_.getNumSubscribers () == 0)
      return;
    served_ = true;
    const std_msgs::UInt8MultiArrayConstPtr model = last_model_;
    // Shared and not changed after publish: a nodelet in the same manager gets it without a copy.
    const auto cloud = boost::make_shared<sensor_msgs::PointCloud2> ();
    try
    {
      *cloud = decodeModelMessage (*model, resampling_, threads_);
    }
    catch (const std::exception& e)  // not only the library's errors: std::bad_alloc ended the node (and a manager)
    {
      // Every bad message is reported: models come rarely, and each one is somebody's mistake.
      if (ros::ok ())
        ROS_ERROR ("[%s] cannot decode %zu bytes: %s; nothing published", name_.c_str (), model->data.size (), e.what ());
      return;
    }
    cloud->header.frame_id = frame_id_;
    cloud->header.stamp = ros::Time::now ();
    cloud_pub_.publish (cloud);
  }
} // namespace pcl_sparse_ros
