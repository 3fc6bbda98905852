// cropsight eval stereo (issue 5): bad-1 / bad-2 (percent of ground-truth pixels off by more than
// 1 / 2 px, a pixel without estimate counting as bad) and time on the Middlebury pairs, for our
// matcher and for plain OpenCV StereoSGBM run in the same process; optionally the paper's SAD /
// SSD 55x55 block-matching baselines.
#include <chrono>
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

template <class F>
nlohmann::json evaluate(const std::vector<stereo::MiddleburyPair>& pairs, F&& match) {
  nlohmann::json j = {{"pairs", nlohmann::json::object()}};
  double s1 = 0, s2 = 0;
  for (const auto& p : pairs) {
    const int nd = ((p.max_disparity + 1 + 15) / 16) * 16;  // search range: the pair's range, rounded up
    const auto t0 = std::chrono::steady_clock::now();
    const stereo::DisparityImage d = match(p, nd);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const auto st = stereo::bad_pixels(d, p.truth, p.name);
    j["pairs"][p.name] = {
        {"bad1", st.bad1}, {"bad2", st.bad2}, {"invalid", st.invalid}, {"ms", ms}, {"num_disparities", nd}};
    s1 += st.bad1;
    s2 += st.bad2;
  }
  j["mean_bad1"] = s1 / double(pairs.size());
  j["mean_bad2"] = s2 / double(pairs.size());
  return j;
}

GrayImage gray(const ColorImage& c) {
  GrayImage g(c.width, c.height);
  for (std::size_t i = 0; i < c.size(); ++i)
    g.data[i] = std::uint8_t((c.data[i].r * 77 + c.data[i].g * 150 + c.data[i].b * 29) >> 8);
  return g;
}

void run(const Options& o) {
  stereo::DisparityConfig cfg;
  // num_disparities is set per pair below (from the pair's true range), so any valid value will do.
  apply_checked_config(cfg, o.common, "", [](const stereo::DisparityConfig& c, const std::string& where) {
    stereo::validate_disparity_config(c, where);
  });
  const auto pairs = stereo::load_middlebury(o.middlebury);
  nlohmann::json j = evaluate(pairs, [&](const stereo::MiddleburyPair& p, int nd) {
    stereo::DisparityConfig c = cfg;
    c.num_disparities = nd;
    return stereo::compute_disparity(p.left, p.right, c, p.name);
  });
  j["opencv_sgbm"] = evaluate(pairs, [&](const stereo::MiddleburyPair& p, int nd) {
    return stereo::opencv_sgbm_disparity(p.left, p.right, nd, 3, p.name);
  });
  if (o.baselines) {
    for (auto cost : {stereo::BlockCost::kSad, stereo::BlockCost::kSsd})
      j[cost == stereo::BlockCost::kSad ? "sad55" : "ssd55"] =
          evaluate(pairs, [&](const stereo::MiddleburyPair& p, int nd) {
            return stereo::block_matching(gray(p.left), gray(p.right), nd, 55, cost, p.name);
          });
  }
  j["rule"] = "percent of ground-truth pixels with |error| > 1 (bad1) or > 2 (bad2) px; no estimate = bad";
  if (o.common.json) {
    print_json(j);
    return;
  }
  std::printf("%-10s %10s %10s %10s | %12s %12s\n", "pair", "bad1 %", "bad2 %", "ms", "sgbm bad1 %", "sgbm bad2 %");
  for (const auto& p : pairs) {
    const auto& a = j["pairs"][p.name];
    const auto& b = j["opencv_sgbm"]["pairs"][p.name];
    std::printf("%-10s %10.2f %10.2f %10.1f | %12.2f %12.2f\n", p.name.c_str(), a["bad1"].get<double>(),
                a["bad2"].get<double>(), a["ms"].get<double>(), b["bad1"].get<double>(), b["bad2"].get<double>());
  }
  std::printf("%-10s %10.2f %10.2f %10s | %12.2f %12.2f\n", "mean", j["mean_bad1"].get<double>(),
              j["mean_bad2"].get<double>(), "", j["opencv_sgbm"]["mean_bad1"].get<double>(),
              j["opencv_sgbm"]["mean_bad2"].get<double>());
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
