/// pcl_sparse/ResampleNodelet: the resample node as a nodelet (as pcl_ros's filters), sharing its code
/// (CloudResampler), so that a driver in the same manager hands over its clouds without copies.

#include <pcl_sparse_ros/cloud_resampler.h>

#include <pcl_sparse/common/error.h>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

namespace pcl_sparse_ros
{
  class ResampleNodelet : public nodelet::Nodelet
  {
  private:
    void
    onInit () override
    {
      try
      {
        resampler_ = std::make_unique<CloudResampler> (getPrivateNodeHandle ());
      }
      catch (const pcl_sparse::Error& e)
      {
        // A bad parameter must not take the manager (and its other nodelets) down: log, stay idle.
        NODELET_FATAL ("%s; this nodelet stays idle", e.what ());
      }
    }

    std::unique_ptr<CloudResampler> resampler_;
  };
} // namespace pcl_sparse_ros

PLUGINLIB_EXPORT_CLASS (pcl_sparse_ros::ResampleNodelet, nodelet::Nodelet)
