// libFuzzer harness: COCO annotation JSON as `train detector --coco` reads it
// (nn::read_coco_detection: images, categories, boxes and polygons), with one 16 x 12 image,
// a.png, present under the images folder so that entries naming it resolve.
#include "cropsight/io/image_io.hpp"
#include "cropsight/nn/detection_dataset.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path images = [] {
    const cropsight::ColorImage image(16, 12, cropsight::Rgb8{10, 200, 10});
    return cropsight::fuzz::write_input(cropsight::io::encode_png(image), "images/a.png").parent_path();
  }();
  const auto path = cropsight::fuzz::write_input(data, size, "annotations.json");
  cropsight::fuzz::expect_error_or_success("read_coco_detection",
                                           [&] { (void)cropsight::nn::read_coco_detection(path, images); });
  cropsight::fuzz::expect_error_or_success("read_coco_detection classes", [&] {
    (void)cropsight::nn::read_coco_detection(path, images, {"bunch", "peduncle"});
  });
  return 0;
}
