// pipeline/potato orientation evaluation on the shared images of the paper's two potatoes (boxes
// from BoardBlobDetector on the RGB image, used for both inputs as in the paper). Skipped when
// ../shared/data is absent. The figures asserted are the ones in docs/pipelines/potatoes.md
// ("Orientation"); the tolerances allow for OpenCV version differences, not for a worse method.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/potato/orientation_dataset.hpp"

namespace cropsight::pipeline::potato {
namespace {

namespace fs = std::filesystem;

const fs::path kDir = fs::path(CROPSIGHT_SHARED_DATA_DIR) / "potato" / "orientation";

eval::OrientationEvaluation run(measure::OrientationSegmentation seg, measure::OrientationAxis axis,
                                measure::OrientationInput input) {
  BoardBlobDetector det;
  measure::OrientationConfig cfg;
  cfg.segmentation = seg;
  cfg.axis = axis;
  cfg.input = input;
  return evaluate_orientation(list_orientation_shots(kDir / "rgb", kDir / "depth"), det, cfg);
}

TEST(OrientationDataset, ListsTheSharedShots) {
  if (!fs::exists(kDir)) GTEST_SKIP() << "no shared potato data at " << kDir;
  const auto shots = list_orientation_shots(kDir / "rgb", kDir / "depth");
  ASSERT_EQ(shots.size(), 15u);  // README: the first potato's 45° high-light shot is missing
  int first = 0;
  for (const auto& s : shots) first += s.potato == 1;
  EXPECT_EQ(first, 7);
  EXPECT_EQ(shots.front().angle_deg, 0);
  EXPECT_EQ(shots.front().rgb.filename(), "image2.png");    // sorted by angle, light, number
  EXPECT_EQ(shots.front().depth.filename(), "image3.png");  // partner numbered one after
}

// A potato (120 x 80 px, brown) on a light grey board, cut in two by a light string 6 px wide,
// with a brown string 6 px wide hanging from it and a knot (a 14 px blob) on that string: the box
// is the whole potato, not its larger half and not the string.
TEST(BoardBlobDetector, BoxIsTheWholePotatoNotItsHalfNorTheString) {
  ColorImage im(640, 480, Rgb8{135, 133, 128});
  const double cx = 320, cy = 240, a = 60, b = 40;
  for (int v = 0; v < im.height; ++v)
    for (int u = 0; u < im.width; ++u) {
      const double x = u + 0.5 - cx, y = v + 0.5 - cy;
      if ((x * x) / (a * a) + (y * y) / (b * b) <= 1) im.at(u, v) = {120, 80, 40};
      if (std::abs(x - 10) < 3 && std::abs(y) < 60) im.at(u, v) = {130, 128, 124};        // light string across
      if (std::abs(y + 0.6 * x) < 3 && x < -50 && x > -200) im.at(u, v) = {110, 85, 60};  // brown string
      if (std::hypot(x + 150, y - 90) < 7) im.at(u, v) = {110, 85, 60};                   // its knot
    }
  BoardBlobDetector det;
  const auto boxes = det.detect({&im, nullptr});
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NEAR(boxes[0].x1, cx - a, 4);
  EXPECT_NEAR(boxes[0].x2, cx + a, 4);
  EXPECT_NEAR(boxes[0].y1, cy - b, 4);
  EXPECT_NEAR(boxes[0].y2, cy + b, 4);
}

TEST(OrientationDataset, MissingFolderNamesIt) {
  try {
    list_orientation_shots("/nonexistent/rgb", "/nonexistent/depth");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "/nonexistent/rgb");
  }
}

// The documented figures (docs/pipelines/potatoes.md, "Orientation"), ± 0.5°: ours + PCA, all 15
// shots and per potato (potato 1 chose ours_closing_fraction; potato 2 is the one not tuned on).
TEST(OrientationDataset, OursMatchesTheDocumentedMae) {
  if (!fs::exists(kDir)) GTEST_SKIP() << "no shared potato data at " << kDir;
  using S = measure::OrientationSegmentation;
  const auto d = run(S::ours, measure::OrientationAxis::pca, measure::OrientationInput::depth);
  EXPECT_NEAR(d.all.mae_deg, 4.3, 0.5);  // 5.4 before the no-depth fill (ours_no_depth_fill_fraction)
  EXPECT_NEAR(d.per_potato[0].mae_deg, 1.8, 0.5);
  EXPECT_NEAR(d.per_potato[1].mae_deg, 6.6, 0.5);
  EXPECT_EQ(d.all.failures, 0);
  const auto r = run(S::ours, measure::OrientationAxis::pca, measure::OrientationInput::rgb);
  EXPECT_NEAR(r.all.mae_deg, 3.5, 0.5);
  EXPECT_NEAR(r.per_potato[0].mae_deg, 1.6, 0.5);
  EXPECT_NEAR(r.per_potato[1].mae_deg, 5.1, 0.5);
  EXPECT_EQ(r.all.failures, 0);
}

// Canny on RGB found no edge on any shared shot before the contrast stretch (the table's row was
// 90 deg, 15 failed): now every shot has a mask, and the error is the paper's order (25.1 deg on RGB).
TEST(OrientationDataset, CannyOnRgbMasksEveryShot) {
  if (!fs::exists(kDir)) GTEST_SKIP() << "no shared potato data at " << kDir;
  using S = measure::OrientationSegmentation;
  const auto r = run(S::canny, measure::OrientationAxis::pca, measure::OrientationInput::rgb);
  EXPECT_EQ(r.all.failures, 0);
  EXPECT_NEAR(r.all.mae_deg, 23.6, 0.5);
}

TEST(OrientationDataset, AllCombinationsTable) {
  if (!fs::exists(kDir)) GTEST_SKIP() << "no shared potato data at " << kDir;
  using S = measure::OrientationSegmentation;
  using A = measure::OrientationAxis;
  using I = measure::OrientationInput;
  for (I in : {I::depth, I::rgb})
    for (S s : {S::canny, S::kmeans, S::ours})
      for (A a : {A::pca, A::ellipse}) {
        const auto e = run(s, a, in);
        std::printf("%-6s %-7s %-8s all %5.1f ± %5.1f  p1 %5.1f  p2 %5.1f  fail %d  %6.2f ms\n",
                    config_name(in).c_str(), config_name(s).c_str(), config_name(a).c_str(), e.all.mae_deg,
                    e.all.std_deg, e.per_potato[0].mae_deg, e.per_potato[1].mae_deg, e.all.failures, e.ms_per_potato);
      }
}

}  // namespace
}  // namespace cropsight::pipeline::potato
