// COCO / VOC detection sets and the training augmentation of the detector.
#include <gtest/gtest.h>

#include <algorithm>

#include "cropsight/core/error.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/nn/detection_augment.hpp"
#include "cropsight/nn/detection_dataset.hpp"
#include "testing/testing.hpp"

namespace {
using cropsight::testing::error_message;
using namespace cropsight;
using namespace cropsight::nn;
using cropsight::testing::TempDir;
using cropsight::testing::write_text;

TEST(DetectionDataset, ReadsCocoBoxesAndFillsPolygonMasks) {
  TempDir t;
  io::write_color(t / "a.png", ColorImage(40, 30, Rgb8{10, 20, 30}));
  write_text(t / "ann.json", R"({"images": [{"id": 7, "file_name": "sub/a.png"}],
    "categories": [{"id": 0, "name": "_background_"}, {"id": 2, "name": "peduncle"}, {"id": 1, "name": "grape"}],
    "annotations": [{"image_id": 7, "category_id": 1, "bbox": [10, 5, 20, 10],
                     "segmentation": [[10, 5, 30, 5, 30, 15, 10, 15]]},
                    {"image_id": 7, "category_id": 2, "bbox": [1, 1, 2, 3]}]})");
  const auto set = read_coco_detection(t / "ann.json", t.path());
  EXPECT_EQ(set.classes, (std::vector<std::string>{"grape", "peduncle"}));
  ASSERT_EQ(set.samples.size(), 1u);
  const auto& s = set.samples[0];
  ASSERT_EQ(s.boxes.size(), 2u);
  EXPECT_FLOAT_EQ(s.boxes[0].x2, 30.f);
  EXPECT_FLOAT_EQ(s.boxes[0].y2, 15.f);
  EXPECT_EQ(s.boxes[1].class_id, 1);
  ASSERT_EQ(s.masks.size(), 2u);
  EXPECT_GT(s.masks[0].at(20, 10), 0);
  EXPECT_EQ(s.masks[0].at(5, 10), 0);
  // Only the named classes, in the order given.
  const auto peds = read_coco_detection(t / "ann.json", t.path(), {"peduncle"});
  ASSERT_EQ(peds.samples[0].boxes.size(), 1u);
  EXPECT_EQ(peds.samples[0].boxes[0].class_id, 0);
}

TEST(DetectionDataset, BadCocoFilesNameTheFileAndTheKey) {
  TempDir t;
  io::write_color(t / "a.png", ColorImage(8, 8));
  write_text(t / "nobox.json", R"({"images": [{"id": 1, "file_name": "a.png"}], "categories": [{"id": 1, "name": "x"}],
    "annotations": [{"image_id": 1, "category_id": 1}]})");
  const std::string e = error_message([&] { read_coco_detection(t / "nobox.json", t.path()); });
  EXPECT_NE(e.find("nobox.json"), std::string::npos) << e;
  EXPECT_NE(e.find("annotations[0]: no 'bbox'"), std::string::npos) << e;
  write_text(t / "noimages.json", R"({"categories": [{"id": 1, "name": "x"}], "annotations": []})");
  EXPECT_NE(error_message([&] { read_coco_detection(t / "noimages.json", t.path()); }).find("no 'images'"),
            std::string::npos);
  write_text(t / "broken.json", "{");
  EXPECT_NE(error_message([&] { read_coco_detection(t / "broken.json", t.path()); }).find("broken.json"),
            std::string::npos);
  write_text(t / "bad.png", "not a png");
  write_text(t / "badimage.json",
             R"({"images": [{"id": 1, "file_name": "bad.png"}], "categories": [{"id": 1, "name": "x"}],
    "annotations": []})");
  EXPECT_NE(error_message([&] { read_coco_detection(t / "badimage.json", t.path()); }).find("bad.png"),
            std::string::npos);
  // Fuzzing finding 22: a polygon holding something other than numbers (here an object) escaped as
  // nlohmann::json::type_error; a coordinate beyond a million pixels would overflow fillPoly's ints.
  for (const std::string poly :
       {R"([2, 3, {"id": 2}, 1, 7, 1])", "[2, 3, 5, 1e300, 7, 1]", R"([2, 3, 5, "1", 7, 1])"}) {
    write_text(t / "poly.json", R"({"images": [{"id": 1, "file_name": "a.png"}], "categories": [{"id": 1, "name": "x"}],
      "annotations": [{"image_id": 1, "category_id": 1, "bbox": [2, 3, 8, 6], "segmentation": [)" +
                                    poly + "]}]}");
    const std::string p = error_message([&] { read_coco_detection(t / "poly.json", t.path()); });
    EXPECT_NE(p.find("annotations[0]: 'segmentation' holds a polygon that is not"), std::string::npos)
        << poly << ": " << p;
  }
}

// Fuzzing finding 21: an image name the system refuses (here longer than NAME_MAX) made
// std::filesystem throw filesystem_error out of the readers; now it is an Error naming the path.
TEST(DetectionDataset, AnImageNameTheSystemRefusesIsAnErrorNamingIt) {
  TempDir t;
  const std::string long_name(300, 'a');
  std::filesystem::create_directories(t / "voc");
  std::filesystem::create_directories(t / "images");
  write_text(t / "voc" / "x.xml", "<annotation><filename>" + long_name +
                                      ".png</filename><size><width>8</width><height>8</height></size></annotation>");
  std::string e = error_message([&] { read_voc_detection(t / "voc", t / "images", {"potato"}); });
  EXPECT_NE(e.find(long_name), std::string::npos) << e;
  EXPECT_NE(e.find("File name too long"), std::string::npos) << e;
  write_text(t / "long.json", R"({"images": [{"id": 1, "file_name": ")" + long_name +
                                  R"(.png"}], "categories": [{"id": 1, "name": "x"}], "annotations": []})");
  e = error_message([&] { read_coco_detection(t / "long.json", t.path()); });
  EXPECT_NE(e.find("File name too long"), std::string::npos) << e;
  e = error_message([&] { io::read_color(t / (long_name + ".png")); });
  EXPECT_NE(e.find("File name too long"), std::string::npos) << e;
}

DetectionSample square_sample() {
  DetectionSample s;
  s.image = ColorImage(64, 48, Rgb8{100, 100, 100});
  s.masks = {GrayImage(64, 48)};
  for (int y = 10; y < 20; ++y)
    for (int x = 8; x < 24; ++x) s.image.at(x, y) = Rgb8{250, 0, 0}, s.masks[0].at(x, y) = 255;
  s.boxes = {{8, 10, 24, 20, 0, 1}};
  return s;
}

TEST(DetectionAugment, AFlipMirrorsTheBoxAndTheMask) {
  DetectionAugmentConfig cfg;
  cfg.mosaic = cfg.copy_paste = 0, cfg.flip = 1;
  cfg.scale_min = cfg.scale_max = 1, cfg.shift = 0;
  cfg.brightness = cfg.contrast = cfg.saturation = 0;
  const auto s = square_sample();
  const auto a = augment_detection(s, {}, cfg, 5);
  ASSERT_EQ(a.boxes.size(), 1u);
  EXPECT_NEAR(a.boxes[0].x1, 40, 1e-4);
  EXPECT_NEAR(a.boxes[0].x2, 56, 1e-4);
  EXPECT_NEAR(a.boxes[0].y1, 10, 1e-4);
  EXPECT_EQ(a.masks[0].at(40, 10), 255);
  EXPECT_EQ(a.masks[0].at(39, 10), 0);
  EXPECT_EQ(a.masks[0].at(55, 19), 255);
  EXPECT_EQ(a.image.at(40, 10), (Rgb8{250, 0, 0}));
}

TEST(DetectionAugment, IsDeterministicAndKeepsBoxesInTheFrame) {
  DetectionAugmentConfig cfg;
  cfg.mosaic = cfg.copy_paste = 1;
  const std::vector<DetectionSample> pool = {square_sample(), square_sample()};
  for (std::uint64_t draw = 0; draw < 20; ++draw) {
    const auto a = augment_detection(pool[0], pool, cfg, draw), b = augment_detection(pool[0], pool, cfg, draw);
    EXPECT_EQ(a.image, b.image);
    ASSERT_EQ(a.boxes.size(), b.boxes.size());
    EXPECT_EQ(a.image.width, 64);
    EXPECT_EQ(a.image.height, 48);
    for (const auto& d : a.boxes) {
      EXPECT_GE(d.x1, 0.f);
      EXPECT_LE(d.x2, 64.f);
      EXPECT_GE(d.width(), 2.f);
    }
  }
}

// The split train / eval / tune-mask-thresholds share: sizes, set order, the same parts for one
// seed, every sample in exactly one part.
TEST(DetectionDataset, HeldOutSplitIsDeterministicAndKeepsTheSetsOrder) {
  std::vector<DetectionSample> samples(10);
  for (int i = 0; i < 10; ++i) samples[std::size_t(i)].name = std::to_string(i);
  const auto names = [](const std::vector<DetectionSample>& part) {
    std::vector<int> out;
    for (const auto& s : part) out.push_back(std::stoi(s.name));
    return out;
  };
  const DetectionSplit a = split_detection_set(samples, 0.2, 3), b = split_detection_set(samples, 0.2, 3);
  ASSERT_EQ(a.val.size(), 2u);
  EXPECT_EQ(a.train.size(), 8u);
  EXPECT_EQ(names(a.val), names(b.val));
  std::vector<int> all = names(a.train);
  EXPECT_TRUE(std::is_sorted(all.begin(), all.end()));
  for (int v : names(a.val)) all.push_back(v);
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(split_detection_set(samples, 0.01, 3).val.size(), 1u);  // a fraction > 0 holds out one
  EXPECT_TRUE(split_detection_set(samples, 0.0, 3).val.empty());
  EXPECT_EQ(error_message([&] { split_detection_set(samples, 1.0, 3); }).rfind("--val-split", 0), 0u);
}

// A training preset's key must name its section: `mask_weight` alone would be ignored.
TEST(DetectionAugment, TrainingConfigReadsBothSectionsAndRefusesOtherKeys) {
  const DetectorTrainingConfig cfg =
      detector_training_config({{"detector.epochs", "3"}, {"augment.flip", "0.1"}}, "preset.yaml");
  EXPECT_EQ(cfg.detector.epochs, 3);
  EXPECT_DOUBLE_EQ(cfg.augment.flip, 0.1);
  EXPECT_NE(error_message([] {
              detector_training_config({{"mask_weight", "2"}}, "preset.yaml");
            }).find("preset.yaml: unknown key 'mask_weight'"),
            std::string::npos);
}

}  // namespace
