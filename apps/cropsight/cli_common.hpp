#pragma once
// Options and output helpers shared by every sub-command.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/output.hpp"

namespace cropsight::cli {

/// --json, --config PRESET and --set key=value, added to a sub-command that takes them.
struct CommonOptions {
  bool json = false;
  std::string config;  ///< preset name (configs/<name>.yaml) or path to a YAML file
  std::vector<std::string> sets;

  /// The preset's values (when --config is given, else `default_preset` if non-empty) overlaid
  /// with --set; keys are dotted paths. Throws Error naming the file or "--set".
  ConfigMap config_map(const std::string& default_preset = "") const;
};

void add_json_flag(CLI::App* cmd, CommonOptions& o);
void add_config_options(CLI::App* cmd, CommonOptions& o);

/// A number for JSON output: NaN and ±inf (undefined figures) become null, which every JSON
/// reader accepts (nlohmann would write them as null too, but only by accident of its dump).
nlohmann::json json_number(double v);

/// Prints `j` as one line of JSON on stdout.
void print_json(const nlohmann::json& j);

/// The bench commands' frames: the first `max_frames` (0: all) of the sequence `dir`, in memory
/// and without their label images (a robot's frames carry no truth). Throws Error("--frames", ...)
/// when `max_frames` is negative or more than `dir` holds, Error(dir, ...) when it has none.
std::vector<RgbdFrame> read_bench_frames(const std::string& dir, int max_frames);

/// --force on a command that writes: replace an earlier cropsight output, never anything else
/// (io/output.hpp has the rule).
void add_force_flag(CLI::App* cmd, bool& force);

/// An older spelling of a flag or option, kept working for one release: hidden from --help, and
/// using it prints one deprecation line on stderr naming the new spelling.
void add_deprecated_flag(CLI::App* cmd, const std::string& old_name, bool& target, const std::string& new_name);
void add_deprecated_option(CLI::App* cmd, const std::string& old_name, std::string& target,
                           const std::string& new_name);

/// The positional SEQ of the first commands (info, export, render), kept for one release: it fills
/// `target` (the --data option's) and prints the deprecation line.
void add_deprecated_positional(CLI::App* cmd, std::string& target);

/// The output policy of `command` ("detect potato"): its --force and the paths it reads, as given
/// on the command line (empty ones are skipped). Every output is checked against it before work.
io::OutputPolicy output_policy(const std::string& command, bool force, const std::vector<std::string>& inputs);

/// "a,b,c" → {"a", "b", "c"}; throws Error(option, ...) when empty or a part is empty.
std::vector<std::string> split_list(const std::string& text, const std::string& option);

/// Progress line on stderr ("\r" overwritten when stderr is a terminal, one line per update otherwise,
/// at most every `min_interval_s`). Silent when `quiet`.
class Progress {
 public:
  Progress(std::string what, long total, bool quiet = false, double min_interval_s = 1.0);
  void update(long done);
  void finish();

 private:
  std::string what_;
  long total_;
  bool quiet_, tty_;
  double min_interval_s_;
  double last_ = -1e9;  // seconds since the start at the last line printed
  long shown_ = -1;     // the last count printed
  Stopwatch clock_;
};

}  // namespace cropsight::cli
