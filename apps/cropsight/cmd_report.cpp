// cropsight report --data SEQ --out page.html: one self-contained HTML page (embedded PNGs,
// inline CSS/SVG) with the sequence summary and renders of a few evenly spaced frames.
// With --model, the broccoli pipeline runs over the sequence: detection, field-map, size and timing
// sections, and where the sequence has ground truth its tracking evaluation (precision-recall,
// size errors, key metrics).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/html_page.hpp"
#include "cropsight/report/sequence_page.hpp"
#include "report_cli.hpp"

namespace cropsight::cli {

namespace report_cmd {
struct ReportOptions {
  CommonOptions common;
  std::string data, out, title;
  std::string model;  // --model: broccoli detection, sizing and map sections
  int frames = 4;
  bool force = false, quiet = false;
};

// The broccoli sections; returns the tracking figures as `eval broccoli --track --json` has them,
// or (no ground truth) the counts the page shows.
nlohmann::json add_broccoli(report::HtmlPage& page, const ReportOptions& o) {
  const BroccoliReportPass pass = broccoli_report_pass(o.data, o.model, o.common, o.frames, o.quiet);
  report::add_broccoli_sections(page, pass.data);
  if (pass.figures) return tracking_json(*pass.figures);
  nlohmann::json counts{{"ground_truth", false}};
  for (const auto& [key, value] : pass.data.metrics) counts[key] = value;
  return counts;
}

void run(const ReportOptions& o) {
  if (o.frames < 1) throw Error("--frames", "must be at least 1");
  // Before the sequence is read or the broccoli pass prints progress.
  io::check_output_file(o.out, output_policy("report", o.force, {o.data, o.model, o.common.config}));
  // The configuration only drives the detection sections; without a model it would be silently
  // ignored, which hides typos and wrong files.
  if (o.model.empty() && (!o.common.config.empty() || !o.common.sets.empty()))
    throw Error(o.common.config.empty() ? "--set" : "--config",
                "only used with --model (the sequence-only report has no settings)");
  const io::SequenceReader reader(o.data);
  const report::SequenceSummary summary = report::summarize_sequence(reader);
  const std::string name = std::filesystem::path(o.data).lexically_normal().filename().string();
  report::HtmlPage page(o.title.empty() ? "cropsight: sequence " + name : o.title);
  report::SequencePageOptions po;
  po.frames_shown = o.frames;
  report::add_sequence_sections(page, reader, summary, po);
  nlohmann::json broccoli;
  if (!o.model.empty()) broccoli = add_broccoli(page, o);
  page.write(o.out);
  const std::string abs = std::filesystem::absolute(o.out).lexically_normal().string();
  if (o.common.json) {
    nlohmann::json j{{"out", abs},
                     {"frames", summary.info.frames},
                     {"frames_shown", report::evenly_spaced_frames(summary.info.frames, o.frames).size()}};
    if (!o.model.empty()) j["broccoli"] = broccoli;
    print_json(j);
  } else
    std::printf("wrote %s\n", abs.c_str());
}
}  // namespace report_cmd

void add_report(CLI::App& app) {
  using namespace report_cmd;
  auto o = std::make_shared<ReportOptions>();
  auto* cmd = app.add_subcommand("report", "Write a self-contained HTML page about a sequence (or: report demo)");
  // Required unless `report demo` runs, so checked in run(): CLI11 would demand them of the parent
  // even when the sub-command is given.
  cmd->add_option("--data", o->data, "Sequence directory (required)");
  cmd->add_option("--out", o->out, "Output HTML file (required)");
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  cmd->add_option("--frames", o->frames, "Number of evenly spaced frames to render (default 4)");
  cmd->add_option("--title", o->title, "Page title");
  cmd->add_option("--model", o->model,
                  "Broccoli model: add detection, precision-recall, field-map, size and timing sections");
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  CLI::App* demo = add_report_demo(*cmd);
  cmd->callback([o, demo] {
    if (demo->parsed()) return;
    if (o->data.empty()) throw Error("--data", "is required (the sequence to report on)");
    if (o->out.empty()) throw Error("--out", "is required (the HTML page to write)");
    run(*o);
  });
}

}  // namespace cropsight::cli
