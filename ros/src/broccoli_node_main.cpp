// cropsight_broccoli_node: see broccoli_node.hpp and docs/ros.md.
#include <ros/ros.h>

#include "broccoli_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "cropsight_broccoli");
  try {
    cropsight::ros_io::BroccoliNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 2;
  }
  return 0;
}
