// libFuzzer harness: stereo calibration YAML of `cropsight stereo calibrate` (stereo::load_calibration).
#include "cropsight/stereo/calibration.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "calibration.yaml");
  cropsight::fuzz::expect_error_or_success("load_calibration",
                                           [&] { (void)cropsight::stereo::load_calibration(path); });
  return 0;
}
