#pragma once
// The broccoli pass of the report commands (`report --model`, `report demo --broccoli`): the
// pipeline and its tracking evaluation over one labelled sequence, and what the report draws.
#include <nlohmann/json.hpp>
#include <string>

#include "cli_common.hpp"
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/report/broccoli_report.hpp"

namespace cropsight::cli {

struct BroccoliReportPass {
  pipeline::broccoli::TrackingFigures figures;
  report::BroccoliReportData data;  ///< with the model and the detector's stage times
};

/// Runs the broccoli pipeline of `model` (CommonOptions: --config, --set) with tracking over the
/// sequence `seq`, keeping `overlay_frames` evenly spaced frames as pictures. Progress on stderr
/// unless `quiet`. Throws Error(seq, ...) for a sequence without labels.
BroccoliReportPass broccoli_report_pass(const std::string& seq, const std::string& model, const CommonOptions& common,
                                        int overlay_frames, bool quiet);

}  // namespace cropsight::cli
