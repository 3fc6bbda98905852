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

void add_force_flag(CLI::App* cmd, bool& force) {
  cmd->add_flag("--force", force,
                "Replace an earlier cropsight output at --out (a folder only while it holds nothing but what "
                "cropsight wrote there; never an input or a user's files)");
}

namespace {
void deprecation_notice(const std::string& old_name, const std::string& new_name) {
  std::fprintf(stderr, "cropsight: warning: %s is deprecated and will be removed; use %s\n", old_name.c_str(),
               new_name.c_str());
}
}  // namespace

void add_deprecated_flag(CLI::App* cmd, const std::string& old_name, bool& target, const std::string& new_name) {
  cmd->add_flag_callback(
         old_name,
         [&target, old_name, new_name] {
           deprecation_notice(old_name, new_name);
           target = true;
         },
         "Deprecated spelling of " + new_name)
      ->group("");
}

void add_deprecated_option(CLI::App* cmd, const std::string& old_name, std::string& target,
                           const std::string& new_name) {
  cmd->add_option_function<std::string>(
         old_name,
         [&target, old_name, new_name](const std::string& v) {
           deprecation_notice(old_name, new_name);
           target = v;
         },
         "Deprecated spelling of " + new_name)
      ->group("");
}

void add_deprecated_positional(CLI::App* cmd, std::string& target) {
  cmd->add_option_function<std::string>(
         "SEQ",
         [&target](const std::string& v) {
           deprecation_notice("a sequence as a positional argument", "--data SEQ");
           target = v;
         },
         "Deprecated spelling of --data SEQ")
      ->group("");
}

io::OutputPolicy output_policy(const std::string& command, bool force, const std::vector<std::string>& inputs) {
  io::OutputPolicy p{command, force, {}};
  for (const std::string& in : inputs)
    if (!in.empty()) p.inputs.emplace_back(in);
  return p;
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
