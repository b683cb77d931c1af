#pragma once
/// \file shutdown.h
/// Ctrl-C (or roslaunch stopping the node) waited for a whole encoding or resampling: 28 s for a million
/// points. The library stops a stage whose progress callback throws.

#include <pcl_sparse/common/error.h>

#include <ros/ros.h>

#include <string>

namespace pcl_sparse_ros
{
  /// \brief A progress callback (setProgressCallback) that stops the stage once ROS is shutting down.
  inline void
  stopWhenShuttingDown (const std::string&, double)
  {
    if (!ros::ok ())
      throw pcl_sparse::Error ("stopped: the node is shutting down");
  }
} // namespace pcl_sparse_ros
