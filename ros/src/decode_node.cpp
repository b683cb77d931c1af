/// pcl_sparse_decode_node: the .psm bytes on ~model (std_msgs/UInt8MultiArray) -> resampled cloud on
/// ~output, in frame ~frame_id.
///
///   rosrun pcl_sparse pcl_sparse_decode_node ~model:=/resample/model _frame_id:=camera _points:=50000

#include <pcl_sparse_ros/model_decoder.h>

#include <pcl_sparse/common/error.h>

#include <ros/ros.h>

int
main (int argc, char** argv)
{
  ros::init (argc, argv, "pcl_sparse_decode");
  // Kept outside the try: when the last NodeHandle goes, ROS shuts down and ROS_FATAL would print nothing.
  const ros::NodeHandle private_nh ("~");
  try
  {
    pcl_sparse_ros::ModelDecoder decoder (private_nh);
    ros::spin ();
  }
  catch (const pcl_sparse::Error& e)
  {
    ROS_FATAL ("[%s] %s", ros::this_node::getName ().c_str (), e.what ());
    return 1;
  }
  return 0;
}
