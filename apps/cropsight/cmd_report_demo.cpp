// cropsight report demo: the demo page (scripts/demo.sh), one self-contained HTML file with a
// chapter per system made from the folders its commands wrote (report/demo_page.hpp has the
// layouts; docs/cli.md, "report demo"). The broccoli chapter runs the broccoli pipeline and its
// tracking evaluation over DIR/seq, as `report --model` does; the others only read files.
#include <cstdio>
#include <filesystem>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/demo_page.hpp"
#include "cropsight/report/sequence_page.hpp"
#include "cropsight/report/sequence_summary.hpp"
#include "report_cli.hpp"

namespace cropsight::cli {

namespace report_demo_cmd {
namespace fs = std::filesystem;

struct ReportDemoOptions {
  CommonOptions common;
  std::string out, title = "cropsight: five systems on simulated data";
  std::string broccoli, model, seedling, potato, grape, objects;
  int frames = 4;
  bool force = false, quiet = false;
};

void add_broccoli_chapter(report::HtmlPage& page, const ReportDemoOptions& o, nlohmann::json& j) {
  const fs::path seq = fs::path(o.broccoli) / "seq";
  BroccoliReportPass pass = broccoli_report_pass(seq.string(), o.model, o.common, o.frames, o.quiet);
  const report::SystemSummary s = report::broccoli_summary(*pass.figures, pass.data, o.broccoli);
  page.chapter("Broccoli heads and field map", "broccoli");
  report::add_system_summary(page, s);
  report::add_broccoli_sections(page, pass.data);
  // The data the pass ran on, as `report` shows it: after the chapter's results.
  const io::SequenceReader reader(seq);
  report::SequencePageOptions po;
  po.frames_shown = o.frames;
  report::add_sequence_sections(page, reader, report::summarize_sequence(reader), po);
  j["broccoli"] = tracking_json(*pass.figures);
}

void run(const ReportDemoOptions& o) {
  if (o.frames < 1) throw Error("--frames", "must be at least 1");
  if (o.broccoli.empty() && o.seedling.empty() && o.potato.empty() && o.grape.empty() && o.objects.empty())
    throw Error("report demo", "give at least one of --broccoli, --seedling, --potato, --grape, --objects");
  // The model is an input only where the broccoli chapter reads it.
  const std::string model = o.broccoli.empty() ? "" : o.model;
  io::check_output_file(
      o.out, output_policy("report demo", o.force, {o.broccoli, model, o.seedling, o.potato, o.grape, o.objects}));
  report::HtmlPage page(o.title);
  page.paragraph(
      "Every figure below was measured by this run on built-in or simulated data; each chapter opens "
      "with its result, then the figures, then the commands that reproduce it.");
  nlohmann::json j;
  if (!o.broccoli.empty()) add_broccoli_chapter(page, o, j);
  report::add_demo_chapters(page, {o.seedling, o.potato, o.grape, o.objects});
  page.write(o.out);
  const std::string abs = fs::absolute(o.out).lexically_normal().string();
  j["out"] = abs;
  if (o.common.json)
    print_json(j);
  else
    std::printf("wrote %s\n", abs.c_str());
}
}  // namespace report_demo_cmd

CLI::App* add_report_demo(CLI::App& report) {
  using namespace report_demo_cmd;
  auto o = std::make_shared<ReportDemoOptions>();
  auto* cmd = report.add_subcommand("demo", "The demo page: a chapter per system from the folders its commands wrote");
  cmd->add_option("--out", o->out, "Output HTML file")->required();
  cmd->add_option("--broccoli", o->broccoli, "Folder holding seq/ (simulate broccoli): heads and field map");
  add_broccoli_model_option(cmd, o->model);
  cmd->add_option("--frames", o->frames, "Broccoli frames shown (default 4)");
  cmd->add_option("--seedling", o->seedling, "Folder of the seedling commands' outputs (docs/cli.md)");
  cmd->add_option("--potato", o->potato, "Folder of the potato commands' outputs (docs/cli.md)");
  cmd->add_option("--grape", o->grape, "Folder of the grape commands' outputs (docs/cli.md)");
  cmd->add_option("--objects", o->objects, "Folder of detect objects' outputs and its images (docs/cli.md)");
  cmd->add_option("--title", o->title, "Page title");
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
  return cmd;
}

}  // namespace cropsight::cli
