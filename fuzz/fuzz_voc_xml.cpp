// libFuzzer harness: Pascal VOC annotation XML, alone (io::read_voc) and as a data
// set folder for `train detector --voc` (nn::read_voc_detection, with one 16 x 12 image, a.png).
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/voc.hpp"
#include "cropsight/nn/detection_dataset.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path images = [] {
    const cropsight::ColorImage image(16, 12, cropsight::Rgb8{10, 200, 10});
    return cropsight::fuzz::write_input(cropsight::io::encode_png(image), "images/a.png").parent_path();
  }();
  const auto path = cropsight::fuzz::write_input(data, size, "voc/a.xml");
  cropsight::fuzz::expect_error_or_success("read_voc", [&] { (void)cropsight::io::read_voc(path); });
  cropsight::fuzz::expect_error_or_success("read_voc_detection", [&] {
    (void)cropsight::nn::read_voc_detection(path.parent_path(), images, {"potato", "bunch"});
  });
  return 0;
}
