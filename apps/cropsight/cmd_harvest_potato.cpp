// cropsight harvest potato: the whole loop per frame of an RGB-D sequence (detect,
// locate, ripeness, select / track, orient) -> one harvest message per frame as a JSON line
// (paper Table 3.2 plus frame, timestamp, target id, state, score). The loop is
// pipeline::potato::Pipeline; this file parses options, reads frames, writes the lines.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <sstream>

#include "bag_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"
#include "potato_cli.hpp"

namespace cropsight::cli {

namespace harvest_potato_cmd {

struct Options {
  CommonOptions common;
  std::string data, out;
  BagTopicOptions topics;
  bool quiet = false, force = false;
};

void run(const Options& o) {
  namespace pp = pipeline::potato;
  // Before the pipeline loads or the loop prints progress.
  if (!o.out.empty()) io::check_output_file(o.out, output_policy("harvest potato", o.force, {o.data, o.common.config}));
  const auto built = make_potato(o.common);
  pp::Pipeline& pipeline = *built;
  const Recording recording(o.data, o.topics);
  const io::SequenceReader seq(recording.sequence());
  std::ostringstream lines;
  nlohmann::json messages = nlohmann::json::array();
  Progress progress("harvest potato", seq.size(), o.quiet || o.common.json || o.out.empty());
  double ms = 0;
  int with_target = 0;
  for (int i = 0; i < seq.size(); ++i) {
    const pp::FrameResult r = pipeline.process(seq.read(i));
    ms += r.timer.total_ms();
    with_target += r.target.detection ? 1 : 0;
    const nlohmann::json message = harvest_json(r.target);
    lines << message.dump() << '\n';
    if (o.common.json && o.out.empty()) messages.push_back(message);
    progress.update(i + 1);
  }
  progress.finish();
  // Without --out and --json, stdout is the per-frame stream (one JSON line a frame); --json is
  // always one object, holding the messages when they went to no file.
  if (o.out.empty() && !o.common.json) {
    std::fputs(lines.str().c_str(), stdout);
    return;
  }
  if (!o.out.empty()) io::write_file_atomic(o.out, lines.str());
  const double fps = ms > 0 ? 1000.0 * seq.size() / ms : 0;
  if (o.common.json) {
    nlohmann::json j{{"frames", seq.size()},
                     {"frames_with_target", with_target},
                     {"ms_per_frame", json_number(ms / std::max(1, seq.size()))},
                     {"fps", json_number(fps)}};
    if (o.out.empty())
      j["messages"] = std::move(messages);
    else
      j["out"] = o.out;
    print_json(j);
  } else
    std::printf("%d frames, a target in %d, %.2f ms a frame (%.0f fps) -> %s\n", seq.size(), with_target,
                ms / std::max(1, seq.size()), fps, o.out.c_str());
}

}  // namespace harvest_potato_cmd

void add_harvest_potato(CLI::App& harvest) {
  using namespace harvest_potato_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd =
      harvest.add_subcommand("potato", "The potato harvest loop on an RGB-D sequence: one harvest message per frame");
  add_recording_options(cmd, o->data, o->topics, "RGB-D sequence folder (docs/formats.md; colour required)");
  cmd->add_option("--out", o->out, "JSON-lines file of the messages (default: stdout)");
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "no progress line");
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
