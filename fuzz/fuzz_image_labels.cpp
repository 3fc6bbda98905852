// libFuzzer harness: other tools' image labels (io/image_labels.hpp) — the input read as a COCO
// file, a CVAT XML file and a labelme folder's one file — and what import then writes from them
// (COCO, YOLO, VOC, the instance label image of images no larger than a megapixel).
#include "cropsight/io/image_labels.hpp"
#include "fuzz_support.hpp"

namespace {
void write_all(const cropsight::io::LabelSet& set) {
  (void)cropsight::io::coco_json(set);
  for (const auto& im : set.images) {
    (void)cropsight::io::yolo_text(im, set.classes);
    (void)cropsight::io::voc_xml(im);
    if (long(im.width) * long(im.height) <= 1000000) (void)cropsight::io::rasterise_instances(im, 1);
    (void)cropsight::io::frame_index_from_name(im.file_name);
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto json = cropsight::fuzz::write_input(data, size, "labels/a.json");
  const auto xml = cropsight::fuzz::write_input(data, size, "cvat/a.xml");
  cropsight::fuzz::expect_error_or_success("read_coco_labels",
                                           [&] { write_all(cropsight::io::read_coco_labels(json)); });
  cropsight::fuzz::expect_error_or_success("read_labelme_labels",
                                           [&] { write_all(cropsight::io::read_labelme_labels(json.parent_path())); });
  cropsight::fuzz::expect_error_or_success("read_cvat_labels",
                                           [&] { write_all(cropsight::io::read_cvat_labels(xml)); });
  return 0;
}
