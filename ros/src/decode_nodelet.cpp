/// pcl_sparse/DecodeNodelet: the decode node as a nodelet, sharing its code (ModelDecoder).

#include <pcl_sparse_ros/model_decoder.h>

#include <pcl_sparse/common/error.h>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

namespace pcl_sparse_ros
{
  class DecodeNodelet : public nodelet::Nodelet
  {
  private:
    void
    onInit () override
    {
      try
      {
        decoder_ = std::make_unique<ModelDecoder> (getPrivateNodeHandle ());
      }
      catch (const pcl_sparse::Error& e)
      {
        NODELET_FATAL ("%s; this nodelet stays idle", e.what ());
      }
    }

    std::unique_ptr<ModelDecoder> decoder_;
  };
} // namespace pcl_sparse_ros

PLUGINLIB_EXPORT_CLASS (pcl_sparse_ros::DecodeNodelet, nodelet::Nodelet)
