# The catkin side of the ROS 1 build (issue 15), included by the top-level CMakeLists.txt before any
# target, and only when catkin_make, catkin build or colcon (catkin type) configures the package.
# catkin_package () makes devel/lib/pcl_sparse the folder of the executables (the nodes and the tools:
# rosrun and roslaunch look there) and devel/lib that of the libraries (the nodelet plugin).
find_package(catkin REQUIRED COMPONENTS roscpp nodelet pluginlib sensor_msgs std_msgs pcl_conversions)
# pluginlib is the ROS 2 line on Debian (only class_list_macros.hpp): it must be a catkin component.
catkin_package(
  INCLUDE_DIRS include
  LIBRARIES pcl_sparse
  DEPENDS PCL)
set(PCL_SPARSE_ROS ON)
