#pragma once
// A whole batch, as `cropsight batch` runs it: plan the manifest, check everything that can be
// checked before submission (recordings, pipeline, geo origins, the output folder), run the
// missing shards on an engine, merge (broccoli: batch_merge.hpp) or concatenate (potato, grape,
// seedling: batch_concat.hpp) when every shard is done, and write DIR/summary.json and report.html.
#include <filesystem>
#include <string>

#include "cropsight/batch/batch_concat.hpp"
#include "cropsight/batch/batch_merge.hpp"
#include "cropsight/batch/engine.hpp"
#include "cropsight/batch/manifest.hpp"
#include "cropsight/batch/slurm_engine.hpp"

namespace cropsight::batch {

struct BatchOptions {
  std::string engine = "local";  ///< "local" or "slurm"
  int workers = 1;               ///< local engine threads
  SlurmRun slurm;                ///< slurm engine settings (options: the manifest's with overrides)
  double row_gap_m = 0.3;        ///< assign_rows's gap (half the narrowest row spacing of the presets)
  bool force = false;            ///< --force: start over in a DIR that is an earlier cropsight output
};

struct BatchResult {
  BatchPlan plan;
  bool resumed = false;  ///< DIR held this batch already
  EngineReport engine;
  bool merged = false;   ///< every shard done, merge (or concatenation) written
  MergeSummary merge;    ///< broccoli
  ConcatSummary concat;  ///< potato, grape, seedling
};

/// Runs the batch into `dir`. Throws Error (manifest, recording, DIR, sbatch) before any shard
/// runs when something is wrong; a shard that fails is reported in the result, not thrown.
BatchResult run_batch(const Manifest& manifest, const std::filesystem::path& dir, const BatchOptions& options,
                      const BatchLog& log = {});

/// summary.json's text for `result` (also what `batch --json` prints).
std::string batch_summary_json(const BatchResult& result);

}  // namespace cropsight::batch
