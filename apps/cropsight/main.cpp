// cropsight CLI entry point: builds the command tree and maps errors to one line + exit code.
//   exit 0  success
//   exit 2  bad input or usage (one line on stderr naming the file/option and the problem)
//   exit 1  unexpected internal failure
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "cropsight/core/error.hpp"

// Long on purpose: the command tree as one table, then the error-to-exit-code mapping.
int main(int argc, char** argv) {
  spdlog::set_pattern("%v");
  spdlog::set_level(spdlog::level::warn);
  CLI::App app{"cropsight: 3D perception for harvesting and weeding robots"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cropsight 0.1.0");

  using namespace cropsight::cli;
  auto* simulate = app.add_subcommand("simulate", "Simulate sequences with exact ground truth");
  simulate->require_subcommand(1);
  add_simulate_broccoli(*simulate);
  add_simulate_potato(*simulate);
  add_simulate_grape(*simulate);
  add_info(app);
  add_export(app);
  add_import(app);
  add_render(app);
  add_report(app);
  add_studio(app);
  // Verbs shared by the pipelines (broccoli, stereo, grape...): each adds its sub-command.
  auto* train = app.add_subcommand("train", "Train a model on labelled data");
  train->require_subcommand(1);
  auto* detect = app.add_subcommand("detect", "Run a trained detector");
  detect->require_subcommand(1);
  auto* eval = app.add_subcommand("eval", "Evaluate a model against ground truth");
  eval->require_subcommand(1);
  auto* bench = app.add_subcommand("bench", "Time pipelines against their reference implementations");
  bench->require_subcommand(1);
  add_train_broccoli(*train);
  add_detect_broccoli(*detect);
  add_eval_broccoli(*eval);
  add_bench_broccoli(*bench);
  add_suggest(app);
  // Grape bunches
  auto* segment = app.add_subcommand("segment", "Label the points of a cloud with a trained model");
  segment->require_subcommand(1);
  add_train_grape(*train);
  add_segment_grape(*segment);
  add_eval_grape(*eval);
  add_roi_cloud(app);
  add_detect_grape(*detect);  // the whole grape pipeline from the camera

  // Broccoli seedlings from stereo
  add_stereo(app);
  add_detect_seedling(*detect);
  add_eval_seedling(*eval);
  add_eval_stereo(*eval);
  add_simulate_seedling(*simulate);

  // Potatoes
  add_detect_potato(*detect);
  add_eval_potato_detection(*eval);
  add_eval_potato_orientation(*eval);
  add_eval_potato(*eval);
  add_eval_potato_tracker(*eval);
  auto* harvest = app.add_subcommand("harvest", "Run a harvest loop: one target message per frame");
  harvest->require_subcommand(1);
  add_harvest_potato(*harvest);
  add_bench_potato(*bench);

  // Our own 2D detector
  add_train_detector(*train);
  add_export_detector(app);
  add_calibrate_detector(app);
  add_detect_objects(*detect);
  add_eval_detector(*eval);

  // Field batches
  add_batch(app);
  add_batch_shard(app);
  add_merge(app);

  // CLI11 reports a mistyped command as "A subcommand is required"; name it instead. Same one
  // level down (cropsight detect brocoli).
  for (CLI::App* level = &app; level;) {
    const int pos = level == &app ? 1 : 2;
    if (argc <= pos || argv[pos][0] == '-') break;
    CLI::App* next = nullptr;
    for (CLI::App* sub : level->get_subcommands({}))
      if (sub->check_name(argv[pos])) next = sub;
    if (!next) {
      std::fprintf(stderr, "cropsight: unknown command '%s%s%s' (see %s--help)\n", pos == 2 ? argv[1] : "",
                   pos == 2 ? " " : "", argv[pos], pos == 2 ? (std::string(argv[1]) + " ").c_str() : "");
      return 2;
    }
    level = pos == 1 && !next->get_subcommands({}).empty() ? next : nullptr;
  }
  // Commands renamed for one release: the old name works, with one line naming the new one.
  if (argc > 1 && std::string(argv[1]) == "calibrate-detector")
    std::fprintf(stderr,
                 "cropsight: warning: calibrate-detector is deprecated and will be removed; use "
                 "tune-mask-thresholds\n");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "cropsight: %s (see --help)\n", e.what());
    return 2;
  } catch (const cropsight::Error& e) {
    std::fprintf(stderr, "cropsight: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A file system refusal (permissions, a file where a folder is expected, a symlink loop) is the
    // user's environment, not a bug: name the path and the reason on one line.
    const std::string where = e.path1().empty() ? std::string("file system") : e.path1().string();
    std::fprintf(stderr, "cropsight: %s: %s\n", where.c_str(), e.code().message().c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cropsight: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
