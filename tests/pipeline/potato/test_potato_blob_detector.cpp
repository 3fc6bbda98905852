// The classical potato detector: synthetic scenes with known answers (a potato on a sheet, a
// string, a blue object, touching potatoes, a notch that must not split, contrast, depth gating) and the shared images
// (AP50 with the colour model refit leaving each image out).
#include "cropsight/pipeline/potato/blob_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/pipeline/potato/colour_fit.hpp"
#include "cropsight/pipeline/potato/detection_eval.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;
using pipeline::potato::BlobConfig;
using pipeline::potato::BlobDetector;

// The default skin colour (Lab mean) in RGB, so the scene does not depend on a guessed colour.
cv::Scalar skin_rgb() {
  cv::Mat lab(1, 1, CV_8UC3,
              cv::Scalar(110, pipeline::potato::BlobConfig{}.mean_a, pipeline::potato::BlobConfig{}.mean_b)),
      rgb;
  cv::cvtColor(lab, rgb, cv::COLOR_Lab2RGB);
  const cv::Vec3b p = rgb.at<cv::Vec3b>(0, 0);
  return {double(p[0]), double(p[1]), double(p[2])};
}

ColorImage to_image(const cv::Mat& rgb) {
  ColorImage im(rgb.cols, rgb.rows);
  std::memcpy(im.data.data(), rgb.data, im.data.size() * 3);
  return im;
}

// A white sheet, one potato (ellipse 40 x 70 px at (150, 200)), a 3-px string of potato colour
// from the top, and a blue object.
cv::Mat scene() {
  cv::Mat m(416, 416, CV_8UC3, cv::Scalar(235, 235, 240));
  cv::ellipse(m, {150, 200}, {20, 35}, 10, 0, 360, skin_rgb(), cv::FILLED);
  cv::line(m, {150, 0}, {150, 170}, skin_rgb(), 3);
  cv::line(m, {300, 0}, {330, 416}, skin_rgb(), 3);
  cv::circle(m, {320, 300}, 30, cv::Scalar(30, 60, 200), cv::FILLED);
  return m;
}

TEST(PotatoBlobDetector, FindsThePotatoNotTheStringOrTheBlueObject) {
  const ColorImage im = to_image(scene());
  pipeline::potato::BlobDetector det;
  const auto d = det.detect({&im, nullptr});
  ASSERT_EQ(d.size(), 1u);
  Detection2D truth;
  // The ellipse's bounding box: half sides sqrt(a² cos² + b² sin²) and sqrt(a² sin² + b² cos²).
  const double c = std::cos(10 * CV_PI / 180), s = std::sin(10 * CV_PI / 180);
  const double hw = std::sqrt(20 * 20 * c * c + 35 * 35 * s * s), hh = std::sqrt(20 * 20 * s * s + 35 * 35 * c * c);
  truth.x1 = float(150 - hw), truth.y1 = float(200 - hh), truth.x2 = float(150 + hw), truth.y2 = float(200 + hh);
  EXPECT_GT(iou(d[0], truth), 0.8) << d[0].x1 << " " << d[0].y1 << " " << d[0].x2 << " " << d[0].y2;
  EXPECT_GT(d[0].score, 0.5f);
  EXPECT_LE(d[0].score, 1.f);
  EXPECT_EQ(det.class_names(), std::vector<std::string>{"potato"});
}

// The box of an axis-aligned ellipse at (cx, cy) with half axes (a, b), as Detection2D.
Detection2D ellipse_box(double cx, double cy, double a, double b) {
  Detection2D d;
  d.x1 = float(cx - a), d.y1 = float(cy - b), d.x2 = float(cx + a + 1), d.y2 = float(cy + b + 1);
  return d;
}

// Each truth box is matched by one detection with IoU above `min_iou`.
void expect_boxes(const std::vector<Detection2D>& dets, const std::vector<Detection2D>& truth, float min_iou) {
  ASSERT_EQ(dets.size(), truth.size());
  for (const Detection2D& t : truth) {
    float best = 0;
    for (const Detection2D& d : dets) best = std::max(best, iou(d, t));
    EXPECT_GT(best, min_iou) << "truth " << t.x1 << " " << t.y1 << " " << t.x2 << " " << t.y2;
  }
}

TEST(PotatoBlobDetector, SplitsTwoPotatoesJoinedByANeck) {
  cv::Mat m(416, 416, CV_8UC3, cv::Scalar(235, 235, 240));
  // 2 px apart, bridged by the closing: one blob with a neck.
  cv::ellipse(m, {150, 200}, {22, 35}, 0, 0, 360, skin_rgb(), cv::FILLED);
  cv::ellipse(m, {196, 205}, {22, 35}, 0, 0, 360, skin_rgb(), cv::FILLED);
  const ColorImage im = to_image(m);
  pipeline::potato::BlobConfig cfg;
  expect_boxes(pipeline::potato::BlobDetector(cfg).detect({&im, nullptr}),
               {ellipse_box(150, 200, 22, 35), ellipse_box(196, 205, 22, 35)}, 0.85f);
  cfg.split_concavity_depth = 0;  // no split: one blob
  EXPECT_EQ(pipeline::potato::BlobDetector(cfg).detect({&im, nullptr}).size(), 1u);
}

// Two potatoes side by side that overlap by 4 px along most of their length (as in the shared
// image 2fea): no neck, the distance transform has one ridge, but the outline has a deep notch at
// each end of the contact.
TEST(PotatoBlobDetector, SplitsTwoPotatoesTouchingAlongAWideEdge) {
  cv::Mat m(416, 416, CV_8UC3, cv::Scalar(235, 235, 240));
  cv::ellipse(m, {200, 200}, {22, 55}, 0, 0, 360, skin_rgb(), cv::FILLED);
  cv::ellipse(m, {236, 215}, {18, 38}, 0, 0, 360, skin_rgb(), cv::FILLED);
  const ColorImage im = to_image(m);
  pipeline::potato::BlobConfig cfg;
  expect_boxes(pipeline::potato::BlobDetector(cfg).detect({&im, nullptr}),
               {ellipse_box(200, 200, 22, 55), ellipse_box(236, 215, 18, 38)}, 0.8f);
  cfg.split_max_depth = 0;
  EXPECT_EQ(pipeline::potato::BlobDetector(cfg).detect({&im, nullptr}).size(), 1u);
}

// One potato with a shallow notch (a string's attachment, an eye) stays one detection.
TEST(PotatoBlobDetector, DoesNotSplitOnePotatoWithANotch) {
  cv::Mat m(416, 416, CV_8UC3, cv::Scalar(235, 235, 240));
  cv::ellipse(m, {200, 200}, {25, 50}, 0, 0, 360, skin_rgb(), cv::FILLED);
  cv::circle(m, {225, 200}, 7, cv::Scalar(235, 235, 240), cv::FILLED);  // notch 7 px deep, radius 25
  const ColorImage im = to_image(m);
  expect_boxes(pipeline::potato::BlobDetector().detect({&im, nullptr}), {ellipse_box(200, 200, 25, 50)}, 0.85f);
}

// The same potato scores lower among dark surroundings than on the light sheet, by the logistic
// of the lightness difference; with contrast_scale = 0 both score alike.
TEST(PotatoBlobDetector, ContrastWithTheBackgroundRanksTheScore) {
  auto on = [](cv::Scalar background) {
    cv::Mat m(416, 416, CV_8UC3, background);
    cv::ellipse(m, {200, 200}, {25, 50}, 0, 0, 360, skin_rgb(), cv::FILLED);
    return to_image(m);
  };
  // Skin L is 110 (8-bit): about 125 below the sheet, ~90 above the black of a root chamber, and
  // level with a grey of the same lightness (clutter that does not stand out).
  const ColorImage sheet = on(cv::Scalar(235, 235, 240)), dark = on(cv::Scalar(20, 20, 20)),
                   level = on(cv::Scalar(105, 105, 105));
  pipeline::potato::BlobConfig cfg;
  cfg.min_score = 0;  // report every blob
  const auto a = pipeline::potato::BlobDetector(cfg).detect({&sheet, nullptr}),
             b = pipeline::potato::BlobDetector(cfg).detect({&dark, nullptr}),
             g = pipeline::potato::BlobDetector(cfg).detect({&level, nullptr});
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  ASSERT_EQ(g.size(), 1u);
  // Darker or lighter than its background: factor ~1 either way; level with it: ~0.5.
  EXPECT_GT(a[0].score, 0.5f);
  EXPECT_NEAR(b[0].score, a[0].score, 0.02f * a[0].score);
  EXPECT_LT(g[0].score, 0.7f * a[0].score);
  cfg.contrast_scale = 0;
  const auto c = pipeline::potato::BlobDetector(cfg).detect({&sheet, nullptr}),
             d = pipeline::potato::BlobDetector(cfg).detect({&level, nullptr});
  ASSERT_EQ(c.size(), 1u);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR(c[0].score, d[0].score, 1e-3);
}

TEST(PotatoBlobDetector, DepthGatesTheForeground) {
  const ColorImage im = to_image(scene());
  Image<float> far(416, 416, 2.5f), near(416, 416, 0.4f), holes(416, 416, 0.f);
  pipeline::potato::BlobDetector det;
  EXPECT_TRUE(det.detect({&im, &far}).empty());  // the room behind the sheet
  EXPECT_EQ(det.detect({&im, &near}).size(), 1u);
  EXPECT_EQ(det.detect({&im, &holes}).size(), 1u);  // no depth: colour decides
  pipeline::potato::BlobConfig cfg;
  cfg.keep_depth_holes = false;
  EXPECT_TRUE(pipeline::potato::BlobDetector(cfg).detect({&im, &holes}).empty());
  Image<float> wrong(100, 100, 0.4f);
  EXPECT_THROW(det.detect({&im, &wrong}), Error);
}

// A potato whose lower half is in shadow (darker than the colour model) in front of a sheet 0.4 m
// behind it, hanging from a root 8 px wide at its own depth. The colour finds the upper half; the
// depth surface completes the box, the opening keeps the root out, and a flat depth (a wall at
// the potato's depth, no rim) completes nothing.
TEST(PotatoBlobDetector, DepthCompletesTheBoxOfAShadedPotato) {
  cv::Mat m(416, 416, CV_8UC3, cv::Scalar(235, 235, 240));
  cv::ellipse(m, {200, 220}, {45, 30}, 0, 0, 360, cv::Scalar(12, 8, 6), cv::FILLED);  // the shadow
  cv::ellipse(m, {200, 220}, {45, 30}, 0, 180, 360, skin_rgb(), cv::FILLED);          // the lit half
  const ColorImage im = to_image(m);
  Image<float> depth(416, 416, 0.8f);
  cv::Mat dm(416, 416, CV_32FC1, depth.data.data());
  cv::line(dm, {200, 0}, {200, 200}, cv::Scalar(0.4), 8);
  cv::ellipse(dm, {200, 220}, {45, 30}, 0, 0, 360, cv::Scalar(0.4), cv::FILLED);
  const Detection2D whole = ellipse_box(200, 220, 45, 30);

  pipeline::potato::BlobConfig off;
  off.depth_completion = 0;
  const auto colour_only = pipeline::potato::BlobDetector(off).detect({&im, &depth});
  ASSERT_EQ(colour_only.size(), 1u);
  EXPECT_LT(iou(colour_only[0], whole), 0.65);  // the upper half

  const auto completed = pipeline::potato::BlobDetector().detect({&im, &depth});
  ASSERT_EQ(completed.size(), 1u);
  EXPECT_GT(iou(completed[0], whole), 0.9)
      << completed[0].x1 << " " << completed[0].y1 << " " << completed[0].x2 << " " << completed[0].y2;
  EXPECT_GT(completed[0].y1, 180.f);  // not up the root

  Image<float> wall(416, 416, 0.4f);
  const auto flat = pipeline::potato::BlobDetector().detect({&im, &wall});
  ASSERT_EQ(flat.size(), 1u);
  EXPECT_NEAR(iou(flat[0], colour_only[0]), 1.0, 1e-6);
}

// A potato on a white board at close range with its shadow beside it: the shadow has the skin's
// hue, inside the colour model, but is grey (saturation chroma / L about 0.1, the skin's 0.26), as
// measured on the shared orientation shots. The saturation test keeps it out of the box.
TEST(PotatoBlobDetector, SaturationKeepsTheGreyShadowOutOfTheBox) {
  auto lab_to_rgb = [](double l, double a, double b) {
    cv::Mat lab(1, 1, CV_8UC3, cv::Scalar(l, a, b)), rgb;
    cv::cvtColor(lab, rgb, cv::COLOR_Lab2RGB);
    const cv::Vec3b p = rgb.at<cv::Vec3b>(0, 0);
    return cv::Scalar(p[0], p[1], p[2]);
  };
  cv::Mat m(240, 320, CV_8UC3, lab_to_rgb(225, 128, 128));
  cv::ellipse(m, {150, 120}, {50, 34}, 0, 0, 360, lab_to_rgb(90, 131, 137), cv::FILLED);  // the shadow, left
  cv::ellipse(m, {175, 120}, {50, 34}, 0, 0, 360, lab_to_rgb(110, 137, 153), cv::FILLED);
  const ColorImage im = to_image(m);
  const Detection2D truth{125, 86, 225, 154, 0, 1.f};
  pipeline::potato::BlobConfig cfg;
  ASSERT_GT(cfg.min_saturation, 0.105);  // the shadow's 9.5 / 90
  {
    pipeline::potato::BlobDetector det(cfg);
    const auto d = det.detect({&im, nullptr});
    ASSERT_FALSE(d.empty());
    EXPECT_GT(iou(d[0], truth), 0.85) << d[0].x1 << " " << d[0].x2;
  }
  cfg.min_saturation = 0;  // the shadow joins the potato and the box grows over it
  pipeline::potato::BlobDetector det(cfg);
  const auto d = det.detect({&im, nullptr});
  ASSERT_FALSE(d.empty());
  EXPECT_LT(iou(d[0], truth), 0.85) << d[0].x1 << " " << d[0].x2;
}

TEST(PotatoBlobDetector, ConfigIsChecked) {
  pipeline::potato::BlobConfig cfg;
  EXPECT_THROW(apply_config(cfg, {{"detector.colour_distance", "3"}}, "--set", "detector."), Error);
  apply_config(cfg, {{"detector.max_colour_distance", "2.5"}}, "--set", "detector.");
  EXPECT_EQ(cfg.max_colour_distance, 2.5);
  EXPECT_THROW(apply_config(cfg, {{"detector.opening_fraction", "-1"}}, "--set", "detector."), Error);
  cfg.cov_ab = 100;  // not positive definite
  EXPECT_THROW(pipeline::potato::BlobDetector{cfg}, Error);
}

// One shared real scene: annotated images with their truth boxes (as Detection2D for the colour fit).
struct SharedSet {
  std::vector<pipeline::potato::AnnotatedImage> set;
  std::vector<ColorImage> images;
  std::vector<std::vector<Detection2D>> boxes;
};

SharedSet load_set(const std::filesystem::path& images, const std::filesystem::path& annotations) {
  SharedSet s;
  s.set = pipeline::potato::load_annotated_images(images, annotations);
  for (const auto& a : s.set) {
    s.images.push_back(io::read_color(a.image));
    s.boxes.emplace_back();
    for (const auto& b : pipeline::potato::truth_boxes(a.truth)) {
      Detection2D d;
      d.x1 = float(b.x1), d.y1 = float(b.y1), d.x2 = float(b.x2), d.y2 = float(b.y2);
      s.boxes.back().push_back(d);
    }
  }
  return s;
}

// The 11 detection images (about 1 m, a sheet in front of a room) and the 15 orientation shots
// (0.3 m, a white board; boxes drawn for the project in data/potato-orientation-boxes).
std::filesystem::path shared_detection_dir() { return cropsight::testing::shared_data_dir() / "potato" / "detection"; }
std::filesystem::path shared_orientation_rgb_dir() {
  return cropsight::testing::shared_data_dir() / "potato" / "orientation" / "rgb";
}
SharedSet load_detection_set() {
  return load_set(shared_detection_dir() / "images", shared_detection_dir() / "annotations_voc");
}
SharedSet load_orientation_set() {
  return load_set(shared_orientation_rgb_dir(), cropsight::testing::source_dir() / "data" / "potato-orientation-boxes");
}

// Images of both scenes in one list, with the scene of each (0 detection, 1 orientation).
struct Pooled {
  std::vector<const ColorImage*> images;
  std::vector<std::vector<Detection2D>> boxes;
  std::vector<std::vector<eval::VocBox>> truth;
  std::vector<int> scene;
};

Pooled pool(const std::vector<const SharedSet*>& sets) {
  Pooled p;
  for (std::size_t k = 0; k < sets.size(); ++k)
    for (std::size_t i = 0; i < sets[k]->set.size(); ++i) {
      p.images.push_back(&sets[k]->images[i]);
      p.boxes.push_back(sets[k]->boxes[i]);
      p.truth.push_back(pipeline::potato::truth_boxes(sets[k]->set[i].truth));
      p.scene.push_back(int(k));
    }
  return p;
}

// AP per scene of `base` with the colour model refit on all the other images of both scenes for
// each one (leave-one-image-out).
std::array<eval::VocApSummary, 2> leave_one_out(const Pooled& p, const pipeline::potato::BlobConfig& base) {
  std::array<std::vector<eval::VocImage>, 2> per_scene;
  for (std::size_t i = 0; i < p.images.size(); ++i) {
    std::vector<const ColorImage*> train_images;
    std::vector<std::vector<Detection2D>> train_boxes;
    for (std::size_t j = 0; j < p.images.size(); ++j)
      if (j != i) train_images.push_back(p.images[j]), train_boxes.push_back(p.boxes[j]);
    pipeline::potato::BlobConfig cfg = base;
    pipeline::potato::fit_potato_colour(train_images, train_boxes).apply_to(cfg);
    pipeline::potato::BlobDetector det(cfg);
    eval::VocImage v;
    v.truth = p.truth[i];
    v.detections = pipeline::potato::detection_boxes(det.detect({p.images[i], nullptr}));
    per_scene[std::size_t(p.scene[i])].push_back(std::move(v));
  }
  return {eval::voc_ap_summary(per_scene[0]), eval::voc_ap_summary(per_scene[1])};
}

eval::VocApSummary score(const SharedSet& s, const pipeline::potato::BlobConfig& cfg) {
  pipeline::potato::BlobDetector det(cfg);
  std::vector<eval::VocImage> v(s.set.size());
  for (std::size_t i = 0; i < s.set.size(); ++i) {
    v[i].truth = pipeline::potato::truth_boxes(s.set[i].truth);
    v[i].detections = pipeline::potato::detection_boxes(det.detect({&s.images[i], nullptr}));
  }
  return eval::voc_ap_summary(v);
}

// AP50 on the two shared scenes. The colour model is refit on the other 25 images for each one
// (leave-one-image-out); the morphology, split, saturation and score thresholds were chosen on
// these images, so no figure here is held out for them (the judges' images are).
TEST(PotatoBlobDetector, SharedImagesLeaveOneOut) {
  CROPSIGHT_REQUIRE_DATA(shared_detection_dir());
  CROPSIGHT_REQUIRE_DATA(shared_orientation_rgb_dir());
  const SharedSet det = load_detection_set(), ori = load_orientation_set();
  const Pooled p = pool({&det, &ori});
  const auto loo = leave_one_out(p, pipeline::potato::BlobConfig{});
  const auto fixed_det = score(det, pipeline::potato::BlobConfig{}),
             fixed_ori = score(ori, pipeline::potato::BlobConfig{});
  std::printf("[ classical ] detection images (11), colour leave-one-out: AP50 %.4f AP75 %.4f mAP50:95 %.4f\n",
              loo[0].ap50, loo[0].ap75, loo[0].map50_95);
  std::printf("[ classical ] orientation shots (15), colour leave-one-out: AP50 %.4f AP75 %.4f mAP50:95 %.4f\n",
              loo[1].ap50, loo[1].ap75, loo[1].map50_95);
  std::printf(
      "[ classical ] shipped defaults (fit on all 26): detection AP50 %.4f AP75 %.4f, orientation AP50 %.4f "
      "AP75 %.4f\n",
      fixed_det.ap50, fixed_det.ap75, fixed_ori.ap50, fixed_ori.ap75);
  // Measured when written (2026-12-05): 0.922, 0.980, 0.925, 0.983. Before (the fit on the 11
  // detection images alone, no saturation test): 0.911 leave-one-out and 0.923 on the detection
  // images, 0.221 on the orientation shots.
  EXPECT_GT(loo[0].ap50, 0.9);
  EXPECT_GT(loo[1].ap50, 0.7);
  EXPECT_GT(fixed_det.ap50, 0.9);
  EXPECT_GT(fixed_ori.ap50, 0.7);

  // The shipped colour model is the fit on all 26 images (to the printed digits).
  const auto fit = pipeline::potato::fit_potato_colour(p.images, p.boxes);
  const pipeline::potato::BlobConfig def;
  EXPECT_NEAR(fit.mean_a, def.mean_a, 0.01);
  EXPECT_NEAR(fit.mean_b, def.mean_b, 0.01);
  EXPECT_NEAR(fit.cov_aa, def.cov_aa, 0.01);
  EXPECT_NEAR(fit.cov_ab, def.cov_ab, 0.01);
  EXPECT_NEAR(fit.cov_bb, def.cov_bb, 0.01);
}

// Across scenes: the colour fitted on one scene alone, scored on the other (held out for the colour
// model; the other thresholds as shipped). The fit on the detection images misses the orientation
// shots' skin (more red, under another light), while the fit on the shots holds on the detection
// images: the reason the shipped model pools both.
TEST(PotatoBlobDetector, ColourFitAcrossScenes) {
  CROPSIGHT_REQUIRE_DATA(shared_detection_dir());
  CROPSIGHT_REQUIRE_DATA(shared_orientation_rgb_dir());
  const SharedSet det = load_detection_set(), ori = load_orientation_set();
  auto fitted_on = [](const SharedSet& s) {
    std::vector<const ColorImage*> im;
    for (const auto& i : s.images) im.push_back(&i);
    pipeline::potato::BlobConfig cfg;
    pipeline::potato::fit_potato_colour(im, s.boxes).apply_to(cfg);
    return cfg;
  };
  const auto det_on_ori = score(ori, fitted_on(det)), ori_on_det = score(det, fitted_on(ori));
  std::printf("[ classical ] colour fit on the detection images, scored on the orientation shots: AP50 %.4f\n",
              det_on_ori.ap50);
  std::printf("[ classical ] colour fit on the orientation shots, scored on the detection images: AP50 %.4f\n",
              ori_on_det.ap50);
  EXPECT_GT(ori_on_det.ap50, 0.85);  // measured 0.870
  // Measured 0.510 against 0.983 for the shipped (pooled) fit: one scene's fit does not carry to the other.
  EXPECT_LT(det_on_ori.ap50 + 0.2, score(ori, pipeline::potato::BlobConfig{}).ap50);
}

// The leave-one-out figures of the thresholds chosen on these images, one at a time around the
// preset (the table in docs/pipelines/potatoes.md). Prints only: a sweep, not a check.
// build/bin/test_pipeline --gtest_also_run_disabled_tests --gtest_filter='*DISABLED_SharedImagesSweep'
TEST(PotatoBlobDetector, DISABLED_SharedImagesSweep) {
  CROPSIGHT_REQUIRE_DATA(shared_detection_dir());
  CROPSIGHT_REQUIRE_DATA(shared_orientation_rgb_dir());
  const SharedSet det = load_detection_set(), ori = load_orientation_set();
  const Pooled s = pool({&det, &ori});
  auto run = [&](const char* key, std::initializer_list<double> values, auto set) {
    for (const double v : values) {
      pipeline::potato::BlobConfig cfg;
      set(cfg, v);
      const auto r = leave_one_out(s, cfg);
      std::printf(
          "[ sweep ] %s %g: leave-one-out AP50 %.4f AP75 %.4f (detection images), %.4f %.4f (orientation shots)\n", key,
          v, r[0].ap50, r[0].ap75, r[1].ap50, r[1].ap75);
    }
  };
  run("split_concavity_depth", {0, 0.3, 0.4, 0.5, 0.6, 0.7},
      [](pipeline::potato::BlobConfig& c, double v) { c.split_concavity_depth = v; });
  run("contrast_scale", {0, 3, 5, 10, 20}, [](pipeline::potato::BlobConfig& c, double v) { c.contrast_scale = v; });
  run("split_min_part_solidity", {0, 0.8, 0.9, 0.95},
      [](pipeline::potato::BlobConfig& c, double v) { c.split_min_part_solidity = v; });
  run("split_max_depth", {1, 2, 3}, [](pipeline::potato::BlobConfig& c, double v) { c.split_max_depth = int(v); });
  run("split_min_part_fraction", {0.1, 0.15, 0.25},
      [](pipeline::potato::BlobConfig& c, double v) { c.split_min_part_fraction = v; });
  run("min_saturation", {0, 0.1, 0.11, 0.12, 0.13, 0.14, 0.15, 0.16},
      [](pipeline::potato::BlobConfig& c, double v) { c.min_saturation = v; });
}

}  // namespace
