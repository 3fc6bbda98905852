#pragma once
// Every sub-command registers itself on its parent verb here. One file per sub-command
// (cmd_<verb>[_<pipeline>].cpp) defines the matching function; main.cpp calls them.
// Each file keeps its options and helpers in a namespace named after it (cmd_eval_stereo.cpp:
// `eval_stereo_cmd`), not an anonymous one: the CLI compiles as unity batches (apps/cropsight/
// CMakeLists.txt), where every file's `Options` and `run` would otherwise meet.
#include <CLI/CLI.hpp>

namespace cropsight::cli {

// Foundation (sequences, simulator)
void add_simulate_broccoli(CLI::App& simulate);
void add_simulate_potato(CLI::App& simulate);
void add_simulate_grape(CLI::App& simulate);
void add_info(CLI::App& app);
void add_export(CLI::App& app);
void add_import(CLI::App& app);
void add_render(CLI::App& app);
void add_report(CLI::App& app);
void add_studio(CLI::App& app);               // the browser studio (src/studio)
CLI::App* add_report_demo(CLI::App& report);  // called by add_report; returns the sub-command

// Broccoli heads: train / detect / eval / bench broccoli
void add_train_broccoli(CLI::App& train);
void add_detect_broccoli(CLI::App& detect);
void add_eval_broccoli(CLI::App& eval);
void add_bench_broccoli(CLI::App& bench);
void add_suggest(CLI::App& app);  // which frames to label next

// Grape bunches: train / segment / eval grape, roi-cloud; detect grape
void add_train_grape(CLI::App& train);
void add_segment_grape(CLI::App& segment);
void add_eval_grape(CLI::App& eval);
void add_roi_cloud(CLI::App& app);
void add_detect_grape(CLI::App& detect);

// Broccoli seedlings from stereo: stereo calibrate|disparity, detect / eval / simulate seedling, eval stereo
void add_stereo(CLI::App& app);
void add_stereo_disparity(CLI::App& parent);  // called by add_stereo
void add_detect_seedling(CLI::App& detect);
void add_eval_seedling(CLI::App& eval);
void add_eval_stereo(CLI::App& eval);
void add_simulate_seedling(CLI::App& simulate);

// Potatoes: detect potato, eval potato-detection, eval potato-orientation, eval potato,
// harvest potato, bench potato
void add_detect_potato(CLI::App& detect);
void add_eval_potato_detection(CLI::App& eval);
void add_eval_potato_orientation(CLI::App& eval);
void add_eval_potato(CLI::App& eval);          // the harvest loop against the simulator's truth
void add_eval_potato_tracker(CLI::App& eval);  // which visual tracker continues a missed target
void add_harvest_potato(CLI::App& harvest);
void add_bench_potato(CLI::App& bench);

// Our own 2D detector: train detector, export-detector, detect objects, eval detector
void add_train_detector(CLI::App& train);
void add_export_detector(CLI::App& app);
void add_calibrate_detector(CLI::App& app);
void add_detect_objects(CLI::App& detect);
void add_eval_detector(CLI::App& eval);

// Field batches: batch (local or Slurm), batch-shard (one array task), merge
void add_batch(CLI::App& app);
void add_batch_shard(CLI::App& app);
void add_merge(CLI::App& app);

}  // namespace cropsight::cli
