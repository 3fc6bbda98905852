// Opening and resuming a batch's output folder (batch/batch_folder.hpp).
#include "cropsight/batch/batch_folder.hpp"

#include <algorithm>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/output.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

namespace {

// The top-level names a batch writes; the marker lists only what lies under them, so a user's
// file added to DIR is never claimed as the batch's (and --force then refuses to replace DIR).
const std::set<std::string> kBatchNames = {"plan.json",         "shards",     "slurm",    "field-map.csv",
                                           "field-map.geojson", "passes.csv", "rows.csv", "summary.json",
                                           "report.html"};

std::vector<std::string> batch_entries(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(dir);
    if (kBatchNames.count(rel.begin()->string())) out.push_back(rel.string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

bool open_batch_folder(const fs::path& dir, const BatchPlan& plan, bool force) {
  io::OutputPolicy policy{"batch", force, {plan.manifest}};
  for (const Shard& s : plan.shards) policy.inputs.push_back(s.sequence);
  io::check_not_an_input(dir, policy);
  const std::string text = plan_json(plan);
  std::error_code ec;
  const io::OutputMarker marker = io::read_output_marker(dir);
  if (!force && marker.present && marker.command == "batch" && fs::exists(dir / "plan.json", ec)) {
    if (io::read_file(dir / "plan.json") != text)
      throw Error(dir.string(),
                  "holds a batch of another plan (the manifest or the recordings changed); give a "
                  "new --out, restore the manifest, or --force to start over");
    return true;
  }
  // New, empty, or (--force) an earlier cropsight output holding only its own files: start over.
  io::check_output_folder(dir, policy);
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec)) fs::remove_all(dir);
  fs::create_directories(dir / "shards");
  io::write_file_atomic(dir / "plan.json", text);
  mark_batch_folder(dir);
  return false;
}

void mark_batch_folder(const fs::path& dir) { io::write_output_marker(dir, "batch", batch_entries(dir)); }

}  // namespace cropsight::batch
