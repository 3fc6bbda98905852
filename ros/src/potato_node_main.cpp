// cropsight_potato_node: see potato_node.hpp and docs/ros.md.
#include <ros/ros.h>

#include "potato_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "cropsight_potato");
  try {
    cropsight::ros_io::PotatoNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 2;
  }
  return 0;
}
