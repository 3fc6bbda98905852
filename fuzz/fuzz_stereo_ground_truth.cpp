// libFuzzer harness: stereo ground truth as `eval stereo` reads it, the same bytes as a
// PFM file and as an 8/16-bit PNG disparity (stereo::read_pfm, stereo::read_ground_truth).
#include "cropsight/stereo/stereo_io.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto pfm = cropsight::fuzz::write_input(data, size, "disp0GT.pfm");
  const auto png = cropsight::fuzz::write_input(data, size, "disp.png");
  cropsight::fuzz::expect_error_or_success("read_pfm", [&] { (void)cropsight::stereo::read_pfm(pfm); });
  cropsight::fuzz::expect_error_or_success("read_ground_truth pfm",
                                           [&] { (void)cropsight::stereo::read_ground_truth(pfm, 2.0); });
  cropsight::fuzz::expect_error_or_success("read_ground_truth png",
                                           [&] { (void)cropsight::stereo::read_ground_truth(png, 256.0); });
  return 0;
}
