// cropsight_seedling_node: see seedling_node.hpp and docs/ros.md.
#include <ros/ros.h>

#include "seedling_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "cropsight_seedling");
  try {
    cropsight::ros_io::SeedlingNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 2;
  }
  return 0;
}
