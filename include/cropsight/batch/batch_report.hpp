#pragma once
// DIR/report.html of a batch: one self-contained page (report::HtmlPage) with the run's summary,
// the merged map (heads as circles of their diameter, harvestable ones in green), heads and
// harvestable heads per pass, the distribution of head diameters, and the shards' run times.
#include <filesystem>

#include "cropsight/batch/batch_run.hpp"

namespace cropsight::batch {

/// The page's HTML for `result`.
std::string batch_report_html(const BatchResult& result);
/// Writes it atomically to `path`.
void write_batch_report(const std::filesystem::path& path, const BatchResult& result);

}  // namespace cropsight::batch
