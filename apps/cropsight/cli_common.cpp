#include "cli_common.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::cli {

ConfigMap CommonOptions::config_map(const std::string& default_preset) const {
  return io::load_preset_with_overrides(config.empty() ? default_preset : config, sets);
}

void add_json_flag(CLI::App* cmd, CommonOptions& o) {
  cmd->add_flag("--json", o.json, "Print one JSON object on stdout instead of text");
}

void add_config_options(CLI::App* cmd, CommonOptions& o) {
  cmd->add_option("--config", o.config, "Preset name (configs/<name>.yaml) or YAML file");
  cmd->add_option("--set", o.sets, "Override a parameter: key=value (repeatable)")->take_all();
}

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void print_json(const nlohmann::json& j) { std::cout << j.dump() << std::endl; }

std::filesystem::path replaceable_output_folder(const std::string& out,
                                                const std::function<bool(const std::string& name)>& own,
                                                const std::string& own_files) {
  namespace fs = std::filesystem;
  fs::path dir = fs::absolute(out).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  std::error_code ec;
  if (!fs::exists(dir, ec)) return dir;
  if (!fs::is_directory(dir)) throw Error(out, "exists and is not a folder");
  for (const auto& e : fs::directory_iterator(dir))
    if (!e.is_regular_file() || !own(e.path().filename().string()))
      throw Error(out, "holds files other than " + own_files + "; give an empty or new folder");
  return dir;
}

std::vector<RgbdFrame> read_bench_frames(const std::string& dir, int max_frames) {
  const io::SequenceReader reader(dir);
  if (max_frames < 0) throw Error("--frames", "must be >= 0 (0: every frame)");
  if (max_frames > reader.size())
    throw Error("--frames", std::to_string(max_frames) + " asked, but " + dir + " has " +
                                std::to_string(reader.size()) + " frames");
  std::vector<RgbdFrame> frames;
  for (int i = 0; i < (max_frames > 0 ? max_frames : reader.size()); ++i) {
    frames.push_back(reader.read(i));
    frames.back().labels = {};
  }
  if (frames.empty()) throw Error(dir, "sequence has no frames");
  return frames;
}

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, ',');) {
    if (part.empty()) throw Error(option, "empty entry in list '" + text + "'");
    out.push_back(part);
  }
  if (out.empty()) throw Error(option, "expects at least one value");
  return out;
}

Progress::Progress(std::string what, long total, bool quiet, double min_interval_s)
    : what_(std::move(what)), total_(total), quiet_(quiet), tty_(::isatty(2) != 0), min_interval_s_(min_interval_s) {}

void Progress::update(long done) {
  if (quiet_ || done == shown_) return;  // finish() after the last update() prints nothing twice
  const double elapsed = clock_.seconds();
  if (elapsed - last_ < min_interval_s_ && done < total_) return;
  last_ = elapsed;
  shown_ = done;
  const double eta = done > 0 ? elapsed * double(total_ - done) / double(done) : 0.0;
  std::fprintf(stderr, "%s%s %ld/%ld (%.0f%%, %.1f s, eta %.1f s)%s", tty_ ? "\r" : "", what_.c_str(), done, total_,
               total_ ? 100.0 * double(done) / double(total_) : 100.0, elapsed, eta, tty_ ? "" : "\n");
  std::fflush(stderr);
}

void Progress::finish() {
  if (quiet_) return;
  update(total_);
  if (tty_) std::fprintf(stderr, "\n");
}

}  // namespace cropsight::cli
