// libFuzzer harness: camera.yaml of a sequence folder (io::read_camera_yaml).
#include "cropsight/io/sequence.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "camera.yaml");
  cropsight::fuzz::expect_error_or_success("read_camera_yaml", [&] { (void)cropsight::io::read_camera_yaml(path); });
  return 0;
}
