// libFuzzer harness: PCD clouds read as unorganised and as organised clouds (io::read_cloud,
// io::read_organized_cloud: PCL's reader behind our checks).
#include "cropsight/io/cloud_io.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "cloud.pcd");
  cropsight::fuzz::expect_error_or_success("read_cloud", [&] { (void)cropsight::io::read_cloud(path); });
  cropsight::fuzz::expect_error_or_success("read_organized_cloud",
                                           [&] { (void)cropsight::io::read_organized_cloud(path); });
  return 0;
}
