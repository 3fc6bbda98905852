// libFuzzer harness: ROS 1 bag files as `cropsight import --bag` and `detect broccoli
// --bag` read them (ros_io::import_bag_sequence: rosbag's reader, then our checks of topics,
// encodings and camera info, into a sequence folder). C++17, like the rest of the ROS code.
#include "cropsight_ros/bag_io.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "input.bag");
  cropsight::ros_io::BagImportOptions o;
  o.bag = path.string();
  o.out = (cropsight::fuzz::scratch_dir() / "imported").string();
  o.overwrite = true;
  cropsight::fuzz::expect_error_or_success("import_bag_sequence",
                                           [&] { (void)cropsight::ros_io::import_bag_sequence(o); });
  return 0;
}
