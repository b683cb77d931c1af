/// pcl_sparse_resample_node: sensor_msgs/PointCloud2 on ~input -> sparse model -> resampled cloud on
/// ~output and the model's .psm bytes on ~model. Parameters: see ros/README section of README.md.
///
///   rosrun pcl_sparse pcl_sparse_resample_node ~input:=/camera/depth/points _points:=100000

#include <pcl_sparse_ros/cloud_resampler.h>

#include <pcl_sparse/common/error.h>

#include <ros/ros.h>

int
main (int argc, char** argv)
{
  ros::init (argc, argv, "pcl_sparse_resample");
  // Kept outside the try: when the last NodeHandle goes, ROS shuts down and ROS_FATAL would print nothing.
  const ros::NodeHandle private_nh ("~");
  try
  {
    pcl_sparse_ros::CloudResampler resampler (private_nh);
    ros::spin ();
  }
  catch (const pcl_sparse::Error& e)
  {
    ROS_FATAL ("[%s] %s", ros::this_node::getName ().c_str (), e.what ());
    return 1;
  }
  return 0;
}
