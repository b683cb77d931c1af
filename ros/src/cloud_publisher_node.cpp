/// pcl_sparse_cloud_publisher: publishes a .pcd or .ply file as sensor_msgs/PointCloud2 on ~output, with
/// every field the file has (organized files stay organized, NaN points stay), for demos, tests and the
/// latency bench. pcl_ros's pcd_to_pointcloud is in Debian (pcl-ros-tools), but without a package.xml,
/// so roslaunch cannot start it; this does the same, and reads PLY range grids too.
///
///   rosrun pcl_sparse pcl_sparse_cloud_publisher _file:=scan.pcd _frame_id:=camera _rate:=1
///
/// Parameters: ~file (required), ~frame_id ("cloud"), ~rate (Hz, default 1; 0 = publish once, latched).
/// Each message is stamped with the time it is published.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse_ros/parameters.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl_conversions/pcl_conversions.h>

#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include <string>

namespace
{
  bool
  endsWith (const std::string& text, const std::string& suffix)
  {
    return text.size () >= suffix.size () && text.compare (text.size () - suffix.size (), suffix.size (), suffix) == 0;
  }

  bool
  loadCloud (const std::string& file, sensor_msgs::PointCloud2& message)
  {
    pcl::PCLPointCloud2 cloud;
    int status = -1;
    if (endsWith (file, ".pcd"))
      status = pcl::io::loadPCDFile (file, cloud);
    else if (endsWith (file, ".ply"))
      status = pcl::io::loadPLYFile (file, cloud);
    else
      ROS_FATAL ("~file '%s' must end in .pcd or .ply", file.c_str ());
    if (status < 0)
      return false;
    pcl_conversions::moveFromPCL (cloud, message);
    return true;
  }
} // namespace

int
main (int argc, char** argv)
{
  ros::init (argc, argv, "pcl_sparse_cloud_publisher");
  ros::NodeHandle private_nh ("~");
  std::string file;
  std::string frame_id;
  double rate = 1.0;
  try
  {
    // roscpp's param () took its fallback silently (_rate:=abc published at 1 Hz), and ros::Rate holds its
    // period in 32-bit seconds (_rate:=1e-12 or nan aborted the node).
    frame_id = pcl_sparse_ros::readString (private_nh, "frame_id", "cloud");
    if (private_nh.hasParam ("rate") && !private_nh.getParam ("rate", rate))
      throw pcl_sparse::Error ("parameter ~rate must be a number");
    if (!(rate == 0.0 || (rate >= 1e-6 && rate <= 1e6)))
      throw pcl_sparse::Error ("parameter ~rate must be 0 (once) or in [1e-6, 1e6] Hz, not " + std::to_string (rate));
  }
  catch (const pcl_sparse::Error& e)
  {
    ROS_FATAL ("%s", e.what ());
    return 1;
  }
  if (!private_nh.getParam ("file", file))
  {
    ROS_FATAL ("usage: pcl_sparse_cloud_publisher _file:=SCAN.{pcd,ply} [_frame_id:=cloud] [_rate:=Hz, 0 = once]");
    return 1;
  }
  sensor_msgs::PointCloud2 message;
  if (!loadCloud (file, message))
  {
    ROS_FATAL ("cannot read '%s'", file.c_str ());
    return 1;
  }
  message.header.frame_id = frame_id;
  ros::Publisher publisher = private_nh.advertise<sensor_msgs::PointCloud2> ("output", 1, rate == 0.0);
  const std::string how = rate == 0.0 ? "once, latched" : "at " + std::to_string (rate) + " Hz";
  ROS_INFO ("publishing %s (%ux%u points) on %s %s", file.c_str (), message.width, message.height,
            publisher.getTopic ().c_str (), how.c_str ());
  if (rate == 0.0)
  {
    message.header.stamp = ros::Time::now ();
    publisher.publish (message);
    ros::spin ();
    return 0;
  }
  ros::Rate loop (rate);
  while (ros::ok ())
  {
    message.header.stamp = ros::Time::now ();
    publisher.publish (message);
    ros::spinOnce ();
    loop.sleep ();
  }
  return 0;
}
