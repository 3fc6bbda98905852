// The messages ros/ generates with gencpp: their MD5 sums are the wire contract with other ROS
// programs (rostopic, rviz plugins, darknet_ros users), so they must equal upstream's.
#include <cropsight_msgs/HarvestTarget.h>
#include <gtest/gtest.h>
#include <vision_msgs/Detection2DArray.h>
#include <vision_msgs/Detection3DArray.h>

#include <string>

namespace {

template <class M>
std::string md5() {
  return ros::message_traits::MD5Sum<M>::value();
}

TEST(RosMessages, VisionMsgsDetection2DArrayMatchesUpstreamNoetic) {
  // The MD5 of vision_msgs/Detection2DArray on the noetic branch.
  EXPECT_EQ(md5<vision_msgs::Detection2DArray>(), "402071f61477de256df9f1aa45e6e4c8");
  EXPECT_EQ(std::string(ros::message_traits::DataType<vision_msgs::Detection2DArray>::value()),
            "vision_msgs/Detection2DArray");
}

TEST(RosMessages, Detection3DArrayDiffersFrom2D) {
  // Its dependencies' definitions (msg/deps/) are checked against Debian's headers by the ctest
  // ros_msg_deps_md5 (ros/msg/check_deps_md5.py).
  EXPECT_EQ(std::string(ros::message_traits::DataType<vision_msgs::Detection3DArray>::value()),
            "vision_msgs/Detection3DArray");
  EXPECT_NE(md5<vision_msgs::Detection3DArray>(), md5<vision_msgs::Detection2DArray>());
}

TEST(RosMessages, HarvestTargetSerialisesTheTable32Fields) {
  cropsight_msgs::HarvestTarget m;
  m.detection = true;
  m.depth_ok = true;
  m.x = 0.1f;
  m.y = -0.2f;
  m.z = 0.5f;
  m.height = 0.07f;
  m.width = 0.09f;
  m.angle = 1.2f;
  m.target_id = 3;
  m.state = cropsight_msgs::HarvestTarget::STATE_TRACKED;
  std::vector<std::uint8_t> buf(ros::serialization::serializationLength(m));
  ros::serialization::OStream out(buf.data(), std::uint32_t(buf.size()));
  ros::serialization::serialize(out, m);
  cropsight_msgs::HarvestTarget back;
  ros::serialization::IStream in(buf.data(), std::uint32_t(buf.size()));
  ros::serialization::deserialize(in, back);
  EXPECT_EQ(back, m);
  EXPECT_EQ(int(back.state), 2);
}

}  // namespace
