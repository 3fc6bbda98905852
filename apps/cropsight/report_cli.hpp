#pragma once
// The broccoli pass of the report commands (`report --model`, `report demo --broccoli`): the
// pipeline and, on a labelled sequence, its tracking evaluation; what the report draws.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/report/broccoli_report.hpp"

namespace cropsight::cli {

struct BroccoliReportPass {
  std::optional<pipeline::broccoli::TrackingFigures> figures;  ///< none: the sequence has no ground truth
  report::BroccoliReportData data;                             ///< with the model and the detector's stage times
};

/// Runs the broccoli pipeline of `model` (CommonOptions: --config, --set) with tracking over the
/// sequence `seq`, keeping `overlay_frames` evenly spaced frames as pictures; with the tracking
/// evaluation where the sequence has labels and groundtruth.json, else what the pipeline found
/// (report/broccoli_run_data.hpp). Progress on stderr unless `quiet`.
BroccoliReportPass broccoli_report_pass(const std::string& seq, const std::string& model, const CommonOptions& common,
                                        int overlay_frames, bool quiet);

}  // namespace cropsight::cli
