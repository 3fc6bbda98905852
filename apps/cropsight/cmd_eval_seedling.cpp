// cropsight eval seedling (issue 5): runs the seedling detector over a simulated data set
// (cropsight simulate seedling) and prints recognition rate (top-view IoU >= 0.5), sensitivity,
// envelope volume ratio and timings; cv::ml::EM is timed on the same down-sampled points as our
// GMM (same K, tolerance and iteration cap). Images are read before timing; I/O is excluded.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include "commands.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/segmentation/gmm.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/rectification.hpp"
#include "cropsight/stereo/seedling_eval.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace {

namespace fs = std::filesystem;

struct Options {
  CommonOptions common;
  std::string data, calib;
  bool quiet = false, no_opencv = false;
};

void run(const Options& o) {
  const auto cfg = seedling_config(o.common);
  const fs::path dir(o.data);
  if (!fs::is_directory(dir)) throw Error(o.data, "data folder not found");
  const auto calib = stereo::load_calibration(o.calib.empty() ? dir / "rig.yaml" : fs::path(o.calib));
  if (!stereo::is_rectified(calib))
    throw Error(o.data, "evaluation expects the simulator's rectified pairs (rig.yaml of an ideal rig)");
  const auto geo = stereo::rectified_geometry(calib);
  std::vector<fs::path> pairs;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && e.path().filename().string().rfind("pair_", 0) == 0) pairs.push_back(e.path());
  std::sort(pairs.begin(), pairs.end());
  if (pairs.empty()) throw Error(o.data, "no pair_* folders (make them with cropsight simulate seedling)");

  Progress progress("eval seedling", long(pairs.size()), o.quiet || o.common.json);
  double recognised = 0, sens = 0, vol = 0, ms_total = 0, ms_sgm = 0, ms_gmm = 0, ms_cv = 0, ll_ours = 0, ll_cv = 0;
  int cv_runs = 0;
  nlohmann::json per = nlohmann::json::array();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const fs::path& p = pairs[k];
    const auto [left, right] = stereo::read_color_pair(p / "left.png", p / "right.png");
    // The simulator writes 16-bit disparity x 256 and an 8-bit mask; read_gray rejects a 16-bit mask.
    const auto truth_disp = stereo::read_disparity(p / "disparity.png", 256.0, 16);
    const GrayImage mask = stereo::read_gray(p / "mask.png");
    nlohmann::json t;
    try {
      t = nlohmann::json::parse(io::read_file(p / "truth.json"));
    } catch (const nlohmann::json::exception& e) {
      throw Error((p / "truth.json").string(), std::string("malformed JSON: ") + e.what());
    }
    stereo::EnvelopeBox env;
    Eigen::Vector3d n;
    double d = 0;
    try {
      env.length = t.at("envelope").at("length_m").get<double>();
      env.width = t.at("envelope").at("width_m").get<double>();
      env.height = t.at("envelope").at("height_m").get<double>();
      const auto nn = t.at("plane").at("normal");
      n = Eigen::Vector3d(nn.at(0).get<double>(), nn.at(1).get<double>(), nn.at(2).get<double>());
      d = t.at("plane").at("d").get<double>();
    } catch (const nlohmann::json::exception& e) {
      throw Error((p / "truth.json").string(), std::string("missing or malformed key: ") + e.what());
    }
    // A zero or non-finite box or plane would make the volume ratio and the top-view IoU meaningless.
    for (const auto& [key, v] : {std::pair{"envelope.length_m", env.length}, std::pair{"envelope.width_m", env.width},
                                 std::pair{"envelope.height_m", env.height}})
      if (!(std::isfinite(v) && v > 0))
        throw Error((p / "truth.json").string(), std::string("'") + key + "' must be a finite number > 0, got " +
                                                     cropsight::detail::format_value(v));
    if (!(n.allFinite() && std::fabs(n.norm() - 1) < 1e-3 && std::isfinite(d)))
      throw Error((p / "truth.json").string(), "'plane' needs a unit normal and a finite d");

    const auto det = stereo::detect_seedling(left, right, geo, cfg, p.string());
    const auto s = stereo::score_seedling(det, truth_disp, mask, geo, n, d, env);
    recognised += s.recognised;
    sens += s.sensitivity;
    vol += s.volume_ratio;
    ms_total += det.timer.total_ms();
    for (const auto& st : det.timer.stages()) {
      if (st.name == "disparity") ms_sgm += st.total_ms;
      if (st.name == "gmm") ms_gmm += st.total_ms;
    }
    nlohmann::json row = {{"pair", p.filename().string()}, {"iou", s.iou},
                          {"sensitivity", s.sensitivity},  {"volume_ratio", s.volume_ratio},
                          {"ms", det.timer.total_ms()},    {"gmm_iterations", det.gmm.iterations}};
    if (!o.no_opencv && int(det.sampled.size()) >= cfg.gmm.components) {
      const auto t0 = std::chrono::steady_clock::now();
      const auto ref = segmentation::fit_gmm_opencv(det.sampled, cfg.gmm, nullptr, p.string());
      ms_cv += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      ll_cv += ref.log_likelihood;
      ll_ours += det.gmm.log_likelihood;
      ++cv_runs;
    }
    per.push_back(row);
    progress.update(long(k + 1));
  }
  progress.finish();
  const double n_pairs = double(pairs.size());
  nlohmann::json j = {{"pairs", int(pairs.size())},     {"recognition_rate", recognised / n_pairs},
                      {"sensitivity", sens / n_pairs},  {"volume_ratio", vol / n_pairs},
                      {"ms_total", ms_total / n_pairs}, {"ms_sgm", ms_sgm / n_pairs},
                      {"ms_gmm", ms_gmm / n_pairs},     {"per_pair", per}};
  if (cv_runs) {
    j["ms_gmm_opencv"] = ms_cv / cv_runs;
    j["gmm_mean_log_likelihood"] = ll_ours / cv_runs;
    j["gmm_opencv_mean_log_likelihood"] = ll_cv / cv_runs;
  }
  if (o.common.json) {
    print_json(j);
    return;
  }
  std::printf("pairs %d: recognition %.1f%%, sensitivity %.1f%%, volume ratio %.1f%%\n", int(pairs.size()),
              100 * recognised / n_pairs, 100 * sens / n_pairs, 100 * vol / n_pairs);
  std::printf("ms per pair: total %.1f, SGM %.1f, GMM %.2f", ms_total / n_pairs, ms_sgm / n_pairs, ms_gmm / n_pairs);
  if (cv_runs) std::printf(", cv::ml::EM on the same points %.2f", ms_cv / cv_runs);
  std::printf("\n");
}

}  // namespace

void add_eval_seedling(CLI::App& eval) {
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand("seedling", "Seedling recognition on simulated stereo pairs (issue 5)");
  cmd->add_option("--data", o->data, "Folder written by cropsight simulate seedling")->required();
  cmd->add_option("--calib", o->calib, "Calibration YAML (default: DATA/rig.yaml)");
  cmd->add_flag("--no-opencv", o->no_opencv, "Skip timing cv::ml::EM on the same points");
  cmd->add_flag("--quiet", o->quiet, "No progress line");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
