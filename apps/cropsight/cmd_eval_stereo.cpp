// cropsight eval stereo: bad-1 / bad-2 (percent of ground-truth pixels off by more
// than 1 / 2 px, a pixel without estimate counting as bad), holes, average error and time on the
// classic Middlebury pairs (--middlebury) and / or any scene folders (--scenes, stereo_scenes.hpp),
// also over the non-occluded pixels where a scene has a right-view truth, for our matcher and for
// plain OpenCV StereoSGBM run in the same process; optionally the paper's SAD / SSD 55x55
// block-matching baselines. The evaluation is stereo::evaluate_middlebury(); this file chooses
// the matchers and formats the figures.
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/stereo/middlebury.hpp"
#include "cropsight/stereo/stereo_scenes.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace eval_stereo_cmd {

struct Options {
  CommonOptions common;
  std::string middlebury, scenes;
  bool baselines = false;
};

// The CLI's JSON form of one matcher's evaluation (keys as before the evaluation moved to the library).
nlohmann::json stats_json(const stereo::BadPixelStats& s) {
  return {{"bad1", json_number(s.bad1)},
          {"bad2", json_number(s.bad2)},
          {"invalid", json_number(s.invalid)},
          {"avg_error", json_number(s.avg_error)}};
}

nlohmann::json to_json(const stereo::MiddleburyEvaluation& e) {
  nlohmann::json j = {{"pairs", nlohmann::json::object()}};
  for (const auto& p : e.pairs) {
    nlohmann::json q = stats_json(p.stats);
    q["ms"] = json_number(p.ms);
    q["num_disparities"] = p.num_disparities;
    if (p.has_nonoccluded) q["nonoccluded"] = stats_json(p.nonoccluded);
    j["pairs"][p.name] = q;
  }
  j["mean_bad1"] = json_number(e.mean_bad1);
  j["mean_bad2"] = json_number(e.mean_bad2);
  j["mean_invalid"] = json_number(e.mean_invalid);
  j["mean_avg_error"] = json_number(e.mean_avg_error);
  if (e.nonoccluded_pairs > 0) {
    j["mean_nonoccluded"] = stats_json(e.mean_nonoccluded);
    j["mean_nonoccluded"]["pairs"] = e.nonoccluded_pairs;
  }
  return j;
}

// The classic pairs, then the scene folders.
std::vector<stereo::MiddleburyPair> load_pairs(const Options& o) {
  if (o.middlebury.empty() && o.scenes.empty()) throw Error("eval stereo", "give --middlebury DIR and/or --scenes DIR");
  std::vector<stereo::MiddleburyPair> pairs;
  if (!o.middlebury.empty()) pairs = stereo::load_middlebury(o.middlebury);
  if (!o.scenes.empty())
    for (auto& p : stereo::load_stereo_scenes(o.scenes)) pairs.push_back(std::move(p));
  return pairs;
}

void print_stats(const stereo::BadPixelStats& s) {
  std::printf(" %7.2f %7.2f %7.2f %7.2f", s.bad1, s.bad2, s.invalid, s.avg_error);
}

void run(const Options& o) {
  stereo::DisparityConfig cfg;
  // num_disparities is set per pair below (from the pair's true range), so any valid value will do.
  apply_checked_config(cfg, o.common, "", [](const stereo::DisparityConfig& c, const std::string& where) {
    stereo::validate_disparity_config(c, where);
  });
  const auto pairs = load_pairs(o);
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
  std::printf("%-10s %5s %7s %7s %7s %7s %8s | %7s %7s %7s %7s | %11s\n", "pair", "range", "bad1 %", "bad2 %",
              "holes %", "avg px", "ms", "nocc b1", "nocc b2", "holes", "avg px", "sgbm bad1 %");
  for (std::size_t i = 0; i < ours.pairs.size(); ++i) {
    const auto &a = ours.pairs[i], &b = sgbm.pairs[i];
    std::printf("%-10s %5d", a.name.c_str(), a.num_disparities);
    print_stats(a.stats);
    std::printf(" %8.1f |", a.ms);
    if (a.has_nonoccluded)
      print_stats(a.nonoccluded);
    else
      std::printf(" %7s %7s %7s %7s", "-", "-", "-", "-");
    std::printf(" | %11.2f\n", b.stats.bad1);
  }
  std::printf("%-10s %5s %7.2f %7.2f %7.2f %7.2f %8s |", "mean", "", ours.mean_bad1, ours.mean_bad2, ours.mean_invalid,
              ours.mean_avg_error, "");
  if (ours.nonoccluded_pairs > 0)
    print_stats(ours.mean_nonoccluded);
  else
    std::printf(" %7s %7s %7s %7s", "-", "-", "-", "-");
  std::printf(" | %11.2f\n", sgbm.mean_bad1);
}

}  // namespace eval_stereo_cmd

void add_eval_stereo(CLI::App& eval) {
  using namespace eval_stereo_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand("stereo", "Disparity accuracy on Middlebury pairs or any scene folders");
  cmd->add_option("--middlebury", o->middlebury, "Folder with tsukuba/ venus/ teddy/ cones/");
  cmd->add_option("--scenes", o->scenes,
                  "Folder of scenes: subfolders with left.png, right.png, gt.{png,pgm,pfm} and scene.yaml (gt_scale, "
                  "max_disparity), or Middlebury 2014 im0.png, im1.png, disp0GT.pfm, calib.txt (ndisp)");
  cmd->add_flag("--baselines", o->baselines, "Also run the paper's SAD / SSD 55x55 block matching");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
