// cropsight_grape_node: see grape_node.hpp and docs/ros.md.
#include <ros/ros.h>

#include "grape_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "cropsight_grape");
  try {
    cropsight::ros_io::GrapeNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 2;
  }
  return 0;
}
