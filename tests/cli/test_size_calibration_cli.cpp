// The size correction a broccoli model records (pipeline/broccoli/size_calibration.hpp): each
// variety weighs the same. Two passes of one simulated field, the second relabelled as another
// variety whose true heads are 30 mm larger, fit to the mean of the two passes' own fits, not to
// a pooled fit that the pass with more sized detections would pull towards itself.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/broccoli/size_calibration.hpp"
#include "testing/testing.hpp"

namespace size_calibration_test {
namespace fs = std::filesystem;
namespace broccoli = cropsight::pipeline::broccoli;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

// A copy of `from` at `to` whose groundtruth.json names `variety` and whose heads are `grow_mm` larger.
void relabel(const fs::path& from, const fs::path& to, const std::string& variety, double grow_mm) {
  fs::copy(from, to, fs::copy_options::recursive);
  auto gt = nlohmann::json::parse(cropsight::io::read_file(to / "groundtruth.json"));
  gt["attributes"]["variety"] = variety;
  for (auto& inst : gt["instances"]) inst["diameter_mm"] = inst["diameter_mm"].get<double>() + grow_mm;
  cropsight::io::write_file_atomic(to / "groundtruth.json", gt.dump());
}

TEST(SizeCalibration, EachVarietyWeighsTheSame) {
  cropsight::testing::TempDir tmp;
  const fs::path a = tmp / "a", b = tmp / "b";
  ASSERT_EQ(run_cli("simulate broccoli --quiet --frames 12 --seed 11 --out " + shell_quoted(a)).exit_code, 0);
  relabel(a, b, "bigger", 30.0);
  const auto pipe = broccoli::make_pipeline({});
  const std::string file = cropsight::io::find_model(broccoli::kDefaultModel).string();
  const std::shared_ptr<const cropsight::learning::Model> model = broccoli::load_model(file);
  const auto fit_a = broccoli::fit_size_correction(model, pipe->config(), {a.string()});
  const auto fit_b = broccoli::fit_size_correction(model, pipe->config(), {b.string()});
  const auto both = broccoli::fit_size_correction(model, pipe->config(), {a.string(), b.string()});
  ASSERT_EQ(both.groups, (std::vector<std::string>{"bigger", "uk"}));
  EXPECT_NEAR(both.hull.scale, 0.5 * (fit_a.hull.scale + fit_b.hull.scale), 1e-9);
  EXPECT_NEAR(both.hull.offset_mm, 0.5 * (fit_a.hull.offset_mm + fit_b.hull.offset_mm), 1e-9);
  EXPECT_NEAR(both.bbox.offset_mm, 0.5 * (fit_a.bbox.offset_mm + fit_b.bbox.offset_mm), 1e-9);
  EXPECT_EQ(both.hull.n, fit_a.hull.n + fit_b.hull.n);
  // The larger truth moves b's line up by 30 mm at every size.
  EXPECT_NEAR(fit_b.hull.offset_mm - fit_a.hull.offset_mm, 30.0, 1e-6);
  EXPECT_NEAR(fit_b.hull.scale, fit_a.hull.scale, 1e-9);
}

}  // namespace size_calibration_test
