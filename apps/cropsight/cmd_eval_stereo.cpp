// cropsight eval stereo (issue 5): bad-1 / bad-2 (percent of ground-truth pixels off by more than
// 1 / 2 px, a pixel without estimate counting as bad) and time on the Middlebury pairs, for our
// matcher and for plain OpenCV StereoSGBM run in the same process; optionally the paper's SAD /
// SSD 55x55 block-matching baselines. The evaluation is stereo::evaluate_middlebury(); this file
// chooses the matchers and formats the figures.
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/stereo/middlebury.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace {

struct Options {
  CommonOptions common;
  std::string middlebury;
  bool baselines = false;
};

// The CLI's JSON form of one matcher's evaluation (keys as before the evaluation moved to the library).
nlohmann::json to_json(const stereo::MiddleburyEvaluation& e) {
  nlohmann::json j = {{"pairs", nlohmann::json::object()}};
  for (const auto& p : e.pairs)
    j["pairs"][p.name] = {{"bad1", json_number(p.stats.bad1)},
                          {"bad2", json_number(p.stats.bad2)},
                          {"invalid", json_number(p.stats.invalid)},
                          {"ms", json_number(p.ms)},
                          {"num_disparities", p.num_disparities}};
  j["mean_bad1"] = json_number(e.mean_bad1);
  j["mean_bad2"] = json_number(e.mean_bad2);
  return j;
}

void run(const Options& o) {
  stereo::DisparityConfig cfg;
  // num_disparities is set per pair below (from the pair's true range), so any valid value will do.
  apply_checked_config(cfg, o.common, "", [](const stereo::DisparityConfig& c, const std::string& where) {
    stereo::validate_disparity_config(c, where);
  });
  const auto pairs = stereo::load_middlebury(o.middlebury);
  const auto ours = stereo::evaluate_middlebury(pairs, [&](const stereo::MiddleburyPair& p, int nd) {
    stereo::DisparityConfig c = cfg;
    c.num_disparities = nd;
    return stereo::compute_disparity(p.left, p.right, c, p.name);
  });
  const auto sgbm = stereo::evaluate_middlebury(pairs, [&](const stereo::MiddleburyPair& p, int nd) {
    return stereo::opencv_sgbm_disparity(p.left, p.right, nd, 3, p.name);
  });
  nlohmann::json j = to_json(ours);
  j["opencv_sgbm"] = to_json(sgbm);
  if (o.baselines) {
    for (auto cost : {stereo::BlockCost::kSad, stereo::BlockCost::kSsd})
      j[cost == stereo::BlockCost::kSad ? "sad55" : "ssd55"] =
          to_json(stereo::evaluate_middlebury(pairs, [&](const stereo::MiddleburyPair& p, int nd) {
            return stereo::block_matching(stereo::grey_levels(p.left), stereo::grey_levels(p.right), nd, 55, cost,
                                          p.name);
          }));
  }
  j["rule"] = "percent of ground-truth pixels with |error| > 1 (bad1) or > 2 (bad2) px; no estimate = bad";
  if (o.common.json) {
    print_json(j);
    return;
  }
  std::printf("%-10s %10s %10s %10s | %12s %12s\n", "pair", "bad1 %", "bad2 %", "ms", "sgbm bad1 %", "sgbm bad2 %");
  for (std::size_t i = 0; i < ours.pairs.size(); ++i) {
    const auto &a = ours.pairs[i], &b = sgbm.pairs[i];
    std::printf("%-10s %10.2f %10.2f %10.1f | %12.2f %12.2f\n", a.name.c_str(), a.stats.bad1, a.stats.bad2, a.ms,
                b.stats.bad1, b.stats.bad2);
  }
  std::printf("%-10s %10.2f %10.2f %10s | %12.2f %12.2f\n", "mean", ours.mean_bad1, ours.mean_bad2, "", sgbm.mean_bad1,
              sgbm.mean_bad2);
}

}  // namespace

void add_eval_stereo(CLI::App& eval) {
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand("stereo", "Disparity accuracy on the Middlebury pairs (issue 5)");
  cmd->add_option("--middlebury", o->middlebury, "Folder with tsukuba/ venus/ teddy/ cones/")->required();
  cmd->add_flag("--baselines", o->baselines, "Also run the paper's SAD / SSD 55x55 block matching");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
