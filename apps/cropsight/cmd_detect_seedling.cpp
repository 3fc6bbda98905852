// cropsight detect seedling: one stereo pair + calibration -> seedling envelope box,
// image mask, top-view mask and per-stage timings. The detection is pipeline::seedling::Pipeline;
// this file parses options, reads the pair, and writes the outputs.

#include <cstdio>
#include <filesystem>
#include <system_error>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/rectification.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace detect_seedling_cmd {

namespace fs = std::filesystem;

struct Options {
  CommonOptions common;
  std::string left, right, calib, out, mask, top_view;
  bool force = false;
};

// The outputs of one run: each is written to a hidden temporary next to its final name, and all
// are renamed into place only after every one was written, so a failing output (an unwritable
// folder, a full disk) leaves none of them behind. Temporaries left over are removed.
class StagedOutputs {
 public:
  StagedOutputs() = default;
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;
  ~StagedOutputs() {
    std::error_code ec;
    for (const auto& [tmp, final_path] : files_) fs::remove(tmp, ec);
  }
  // `write(tmp)` writes the file; the temporary keeps the extension so OpenCV picks the format.
  template <class F>
  void stage(const fs::path& path, F&& write) {
    fs::path tmp = io::temporary_sibling(path);  // the one temporary name (io/files.hpp)
    tmp += path.extension();
    files_.emplace_back(tmp, path);
    try {
      write(tmp);
    } catch (const Error& e) {
      throw Error(path.string(), e.problem());  // name the user's file, not the temporary
    }
  }
  void commit() {
    for (auto& [tmp, final_path] : files_) {
      std::error_code ec;
      fs::rename(tmp, final_path, ec);
      if (ec) throw Error(final_path.string(), "cannot write: " + ec.message());
      tmp.clear();
    }
  }

 private:
  std::vector<std::pair<fs::path, fs::path>> files_;  // temporary, final
};

void check_json_output(const std::string& path) {
  if (fs::is_directory(path) || !fs::path(path).has_filename())
    throw Error(path, "is a folder; --out needs a file name such as result.json");
}

void run(const Options& o) {
  // Options and outputs first: a bad one must fail before the (slow) detection, not after it.
  if (!o.out.empty()) check_json_output(o.out);
  if (!o.mask.empty()) stereo::check_image_output(o.mask, "--mask", false);
  if (!o.top_view.empty()) stereo::check_image_output(o.top_view, "--top-view", false);
  io::OutputPolicy policy = output_policy("detect seedling", o.force, {o.left, o.right, o.calib, o.common.config});
  for (const std::string& out : {o.out, o.mask, o.top_view})
    if (!out.empty()) {
      io::check_output_file(out, policy);
      policy.inputs.emplace_back(out);  // no two outputs on one path
    }
  const auto seedlings = seedling_pipeline(o.common);
  const auto calib = stereo::load_calibration(o.calib);
  auto [l, r] = stereo::read_color_pair(o.left, o.right);
  if (l.width != calib.width || l.height != calib.height)
    throw Error(o.left, "image size differs from the calibration " + o.calib);
  const auto pair = stereo::rectify_pair(calib, std::move(l), std::move(r), o.left);
  const auto det = seedlings.process(pair.left, pair.right, pair.geometry, o.left);
  nlohmann::json j = seedling_json(det);
  j["left"] = o.left;
  j["right"] = o.right;
  {
    StagedOutputs staged;
    if (!o.mask.empty()) staged.stage(o.mask, [&](const fs::path& t) { stereo::write_gray_png(t, det.image_mask); });
    if (!o.top_view.empty() && !det.top_view.mask.empty())
      staged.stage(o.top_view, [&](const fs::path& t) { stereo::write_gray_png(t, det.top_view.mask); });
    if (!o.out.empty()) staged.stage(o.out, [&](const fs::path& t) { io::write_file_atomic(t, j.dump(2) + "\n"); });
    staged.commit();
  }
  if (o.common.json) {
    print_json(j);
  } else if (det.found) {
    std::printf("seedling: %.1f x %.1f x %.1f mm (volume %.1f cm^3), %zu points, %.1f ms\n", det.envelope.length * 1e3,
                det.envelope.width * 1e3, det.envelope.height * 1e3, det.envelope.volume() * 1e6, det.points.size(),
                det.timer.total_ms());
  } else {
    std::printf("no seedling found (%.1f ms)\n", det.timer.total_ms());
  }
}

}  // namespace detect_seedling_cmd

void add_detect_seedling(CLI::App& detect) {
  using namespace detect_seedling_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = detect.add_subcommand("seedling", "Recognise a broccoli seedling in a stereo pair");
  cmd->add_option("--left", o->left, "Left image")->required();
  cmd->add_option("--right", o->right, "Right image")->required();
  cmd->add_option("--calib", o->calib, "Stereo calibration YAML (cropsight stereo calibrate)")->required();
  cmd->add_option("--out", o->out, "Result JSON to write");
  cmd->add_option("--mask", o->mask, "Left-image seedling mask PNG to write");
  cmd->add_option("--top-view", o->top_view, "Top-view mask PNG to write (soil-plane grid)");
  add_force_flag(cmd, o->force);
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
