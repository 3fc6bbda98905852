// Other tools' image labels (io/image_labels.hpp): COCO, labelme and CVAT read into one form,
// written back as COCO / YOLO / VOC, rasterised into instance label images, and written onto a
// depth sequence's frames; every malformed input is an Error naming its file.
#include "cropsight/io/image_labels.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/voc.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using cropsight::testing::TempDir;
using cropsight::testing::write_text;

namespace image_labels_test {

// Two images of 16 × 12: a 4 × 3 polygon head on the first, a box head and a box leaf on the second.
const char* const kCoco = R"({"images": [{"id": 7, "file_name": "color/000001.png", "width": 16, "height": 12},
  {"id": 9, "file_name": "000003.png", "width": 16, "height": 12}],
 "categories": [{"id": 2, "name": "leaf"}, {"id": 1, "name": "head"}],
 "annotations": [{"id": 1, "image_id": 7, "category_id": 1, "segmentation": [[2, 3, 6, 3, 6, 6, 2, 6]], "bbox": [2, 3, 4, 3]},
  {"id": 2, "image_id": 9, "category_id": 1, "bbox": [8, 2, 3, 2]},
  {"id": 3, "image_id": 9, "category_id": 2, "bbox": [0, 0, 2, 2]}]})";

template <typename Fn>
void expect_error_naming(Fn&& fn, const std::string& needle) {
  try {
    fn();
    ADD_FAILURE() << "no error; expected one naming " << needle;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

long count_id(const LabelImage& im, int id) {
  long n = 0;
  for (auto v : im.data) n += v == id;
  return n;
}

}  // namespace image_labels_test

using namespace image_labels_test;

TEST(ImageLabels, ReadsCocoPolygonsAndBoxes) {
  TempDir t;
  write_text(t / "c.json", kCoco);
  const io::LabelSet set = io::read_coco_labels(t / "c.json");
  EXPECT_EQ(set.classes, (std::vector<std::string>{"head", "leaf"})) << "categories by id";
  ASSERT_EQ(set.images.size(), 2u);
  EXPECT_EQ(set.images[0].file_name, "color/000001.png");
  ASSERT_EQ(set.images[0].shapes.size(), 1u);
  const io::LabelShape& p = set.images[0].shapes[0];
  ASSERT_EQ(p.polygons.size(), 1u);
  EXPECT_EQ(p.polygons[0].size(), 4u);
  EXPECT_DOUBLE_EQ(p.x1, 2);
  EXPECT_DOUBLE_EQ(p.y2, 6);
  const io::LabelShape& b = set.images[1].shapes[0];
  EXPECT_TRUE(b.polygons.empty());
  EXPECT_DOUBLE_EQ(b.x2, 11);
  EXPECT_EQ(set.images[1].shapes[1].label, "leaf");
}

TEST(ImageLabels, MalformedCocoNamesFileAndKey) {
  TempDir t;
  auto bad = [&](const std::string& text, const std::string& needle) {
    write_text(t / "bad.json", text);
    expect_error_naming([&] { io::read_coco_labels(t / "bad.json"); }, needle);
  };
  bad("{", "malformed JSON");
  bad(R"({"images": []})", "'annotations'");
  const std::string head = R"({"images": [{"id": 1, "file_name": "a.png", "width": 4, "height": 4}],
    "categories": [{"id": 1, "name": "head"}], "annotations": [)";
  bad(head + R"({"image_id": 2, "category_id": 1, "bbox": [0, 0, 1, 1]}]})", "annotations[0]: image_id");
  bad(head + R"({"image_id": 1, "category_id": 1, "bbox": [0, 0, -1, 1]}]})", "negative width");
  bad(head + R"({"image_id": 1, "category_id": 1, "segmentation": [[0, 0, 1, 1]]}]})", "at least 3 points");
  bad(head + R"({"image_id": 1, "category_id": 1}]})", "no polygon and no 'bbox'");
  bad(R"({"images": [{"id": 1, "file_name": "a.png", "width": 0, "height": 4}], "categories": [], "annotations": []})",
      "'width'");
  expect_error_naming([&] { io::read_coco_labels(t / "missing.json"); }, "missing.json");
}

TEST(ImageLabels, ReadsLabelmeRectanglesAndPolygons) {
  TempDir t;
  std::filesystem::create_directory(t / "lm");
  write_text(t / "lm" / "b.json", R"({"imagePath": "000004.png", "imageWidth": 16, "imageHeight": 12, "shapes": [
    {"label": "head", "shape_type": "rectangle", "points": [[9, 8], [3, 2]]},
    {"label": "head", "shape_type": "polygon", "points": [[1, 1], [4, 1], [4, 5]]}]})");
  write_text(t / "lm" / "a.json", R"({"imagePath": "000002.png", "imageWidth": 16, "imageHeight": 12, "shapes": []})");
  const io::LabelSet set = io::read_labelme_labels(t / "lm");
  ASSERT_EQ(set.images.size(), 2u);
  EXPECT_EQ(set.images[0].file_name, "000002.png") << "files in name order";
  const auto& r = set.images[1].shapes[0];
  EXPECT_DOUBLE_EQ(r.x1, 3);
  EXPECT_DOUBLE_EQ(r.y2, 8);
  EXPECT_EQ(set.images[1].shapes[1].polygons[0].size(), 3u);
  write_text(t / "lm" / "c.json", R"({"imagePath": "x.png", "imageWidth": 16, "imageHeight": 12, "shapes": [
    {"label": "head", "shape_type": "circle", "points": [[1, 1], [4, 1]]}]})");
  expect_error_naming([&] { io::read_labelme_labels(t / "lm"); }, "c.json: shapes[0]: shape_type 'circle'");
  expect_error_naming([&] { io::read_labelme_labels(t / "none"); }, "none");
}

TEST(ImageLabels, ReadsCvatBoxesAndPolygons) {
  TempDir t;
  write_text(t / "c.xml", R"(<?xml version="1.0"?><annotations><version>1.1</version>
    <image id="0" name="frame_000005.png" width="16" height="12">
      <box label="head" occluded="0" xtl="1.5" ytl="2" xbr="5" ybr="6"/>
      <polygon label="head" points="8,2;12,2;12,6"/><tag label="sunny"/></image></annotations>)");
  const io::LabelSet set = io::read_cvat_labels(t / "c.xml");
  ASSERT_EQ(set.images.size(), 1u);
  ASSERT_EQ(set.images[0].shapes.size(), 2u);
  EXPECT_DOUBLE_EQ(set.images[0].shapes[0].x1, 1.5);
  EXPECT_EQ(set.images[0].shapes[1].polygons[0].size(), 3u);
  write_text(t / "bad.xml", R"(<annotations><image name="a.png" width="4" height="4">
    <polygon label="head" points="1,1;2;3,3"/></image></annotations>)");
  expect_error_naming([&] { io::read_cvat_labels(t / "bad.xml"); }, "image 0 <polygon>: points '2'");
  // Found by fuzzing: a name that is not UTF-8 went on into the COCO JSON, whose writer threw.
  write_text(t / "latin1.xml", "<annotations><image name=\"frame\xb6_1.png\" width=\"4\" height=\"4\"/></annotations>");
  expect_error_naming([&] { io::read_cvat_labels(t / "latin1.xml"); }, "image 0: attribute name is not UTF-8");
  write_text(t / "huge.xml", R"(<annotations><image name="a.png" width="1e300" height="4"/></annotations>)");
  expect_error_naming([&] { io::read_cvat_labels(t / "huge.xml"); }, "whole numbers of pixels");
  write_text(t / "root.xml", "<annotation/>");
  expect_error_naming([&] { io::read_cvat_labels(t / "root.xml"); }, "<annotations>");
}

TEST(ImageLabels, CocoVocAndYoloWriteWhatWasRead) {
  TempDir t;
  write_text(t / "c.json", kCoco);
  const io::LabelSet set = io::read_coco_labels(t / "c.json");
  io::write_file_atomic(t / "again.json", io::coco_json(set));
  const io::LabelSet again = io::read_coco_labels(t / "again.json");
  ASSERT_EQ(again.classes, set.classes);
  ASSERT_EQ(again.images.size(), set.images.size());
  for (std::size_t i = 0; i < set.images.size(); ++i)
    for (std::size_t k = 0; k < set.images[i].shapes.size(); ++k) {
      EXPECT_EQ(again.images[i].shapes[k].label, set.images[i].shapes[k].label);
      EXPECT_EQ(again.images[i].shapes[k].polygons, set.images[i].shapes[k].polygons);
      EXPECT_DOUBLE_EQ(again.images[i].shapes[k].x2, set.images[i].shapes[k].x2);
    }
  EXPECT_EQ(io::yolo_text(set.images[1], set.classes),
            "0 0.59375 0.25 0.1875 0.1666666667\n1 0.0625 0.08333333333 0.125 0.1666666667\n");
  io::write_file_atomic(t / "b.xml", io::voc_xml(set.images[1]));
  const io::VocAnnotation voc = io::read_voc(t / "b.xml");
  EXPECT_EQ(voc.width, 16);
  ASSERT_EQ(voc.objects.size(), 2u);
  EXPECT_EQ(voc.objects[1].name, "leaf");
  EXPECT_DOUBLE_EQ(voc.objects[0].xmin, 8);
  EXPECT_DOUBLE_EQ(voc.objects[0].ymax, 4);
}

TEST(ImageLabels, RasterisesPixelCentresInsideEachShape) {
  io::ImageLabels im{"a.png", 16, 12, {}};
  io::LabelShape box{"head", 1, 1, 4, 3, {}};                                     // 3 × 2 pixels
  io::LabelShape poly{"head", 0, 0, 0, 0, {{{8, 2}, {14, 2}, {14, 6}, {8, 6}}}};  // 6 × 4 pixels
  io::LabelShape over{"head", 3, 1, 5, 2, {}};  // drawn last: takes pixel (3, 1) from the box
  im.shapes = {box, poly, over};
  const LabelImage l = io::rasterise_instances(im, 5);
  EXPECT_EQ(count_id(l, 5), 5);
  EXPECT_EQ(count_id(l, 6), 24);
  EXPECT_EQ(count_id(l, 7), 2);
  EXPECT_EQ(l.at(3, 1), 7);
  EXPECT_EQ(l.at(0, 0), 0);
  EXPECT_THROW(io::rasterise_instances(im, 65534), Error) << "ids stay within 16 bits";
}

TEST(ImageLabels, ShapesFarBeyondTheImageAreClippedToIt) {
  // A coordinate beyond int's range (a corrupt or hand-edited file) covers up to the image edge.
  io::ImageLabels im{"a.png", 16, 12, {}};
  im.shapes = {io::LabelShape{"head", 8, 2, 8.9e45, 4, {}}, io::LabelShape{"head", -1e300, 10, 2, 1e300, {}},
               io::LabelShape{"head", 0, 0, std::nan(""), 1, {}}};
  const LabelImage l = io::rasterise_instances(im, 1);
  EXPECT_EQ(count_id(l, 1), 8 * 2);
  EXPECT_EQ(count_id(l, 2), 2 * 2);
  EXPECT_EQ(count_id(l, 3), 0) << "a NaN bound covers nothing";
}

TEST(ImageLabels, FrameIndexFromName) {
  EXPECT_EQ(io::frame_index_from_name("color/000012.png"), 12);
  EXPECT_EQ(io::frame_index_from_name("frame_7_rgb.jpg"), 7);
  EXPECT_EQ(io::frame_index_from_name("left.png"), -1);
}

TEST(ImageLabels, WritesTheLabelledFramesAsANewSequence) {
  TempDir t;
  const CameraIntrinsics cam = cropsight::testing::fixture_camera();
  {
    io::SequenceWriter w(t / "seq", cam);
    for (int i = 0; i < 5; ++i) w.write(cropsight::testing::fixture_frame(i, cam, true, false));
    w.finish();
  }
  write_text(t / "c.json", kCoco);
  const io::LabelSet set = io::read_coco_labels(t / "c.json");
  const auto s = io::write_labelled_sequence(t / "seq", set, {"head"}, t / "out", {"import", false, {}}, "c.json");
  EXPECT_EQ(s.frames, 2);
  EXPECT_EQ(s.instances, 2) << "the leaf is not a head";
  EXPECT_EQ(s.source_frames, (std::vector<int>{1, 3}));
  const io::SequenceReader out(t / "out");
  ASSERT_EQ(out.size(), 2);
  EXPECT_TRUE(out.info().has_labels);
  EXPECT_EQ(out.groundtruth().attributes.at("source_frames"), "1,3");
  const RgbdFrame f0 = out.read(0), src = io::SequenceReader(t / "seq").read(1);
  EXPECT_EQ(f0.depth.data, src.depth.data) << "frame 1 of the input became frame 0";
  EXPECT_EQ(count_id(f0.labels, 1), 12);
  EXPECT_EQ(count_id(out.read(1).labels, 2), 6);

  auto refused = [&](const std::string& coco, const std::string& needle) {
    write_text(t / "bad.json", coco);
    expect_error_naming(
        [&] {
          io::write_labelled_sequence(t / "seq", io::read_coco_labels(t / "bad.json"), {}, t / "out2",
                                      {"import", false, {}}, "bad.json");
        },
        needle);
    EXPECT_FALSE(std::filesystem::exists(t / "out2"));
  };
  const std::string tail = R"(, "categories": [], "annotations": []})";
  refused(R"({"images": [{"id": 1, "file_name": "000009.png", "width": 16, "height": 12}])" + tail, "past the end");
  refused(R"({"images": [{"id": 1, "file_name": "000001.png", "width": 8, "height": 12}])" + tail, "8x12");
  refused(R"({"images": [{"id": 1, "file_name": "left.png", "width": 16, "height": 12}])" + tail, "no frame number");
  refused(R"({"images": [{"id": 1, "file_name": "a/000001.png", "width": 16, "height": 12},
    {"id": 2, "file_name": "b/000001.png", "width": 16, "height": 12}])" +
              tail,
          "labelled twice");
}
