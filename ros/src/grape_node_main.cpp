// cropsight_grape_node: see grape_node.hpp and docs/ros.md.
#include <ros/ros.h>

#include <cstdio>

#include "grape_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "cropsight_grape");
  try {
    cropsight::ros_io::GrapeNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    // Also to stderr: once the node's handles are gone, roscpp has shut down and rosconsole
    // prints nothing, so a node that cannot start would exit without saying why.
    std::fprintf(stderr, "cropsight_grape_node: %s\n", e.what());
    ROS_FATAL("%s", e.what());
    return 2;
  }
  return 0;
}
