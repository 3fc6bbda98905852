// Opening and resuming a batch's output folder (batch/batch_folder.hpp).
#include "cropsight/batch/batch_folder.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/output.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

bool open_batch_folder(const fs::path& dir, const BatchPlan& plan) {
  io::OutputPolicy policy{"batch", false, {plan.manifest}};
  for (const Shard& s : plan.shards) policy.inputs.push_back(s.sequence);
  io::check_not_an_input(dir, policy);
  const std::string text = plan_json(plan);
  std::error_code ec;
  if (fs::exists(dir / "plan.json", ec)) {
    const io::OutputMarker marker = io::read_output_marker(dir);
    if (!marker.present || marker.command != "batch")
      throw Error(dir.string(), "holds a plan.json but no batch marker; give a new --out");
    if (io::read_file(dir / "plan.json") != text)
      throw Error(dir.string(),
                  "holds a batch of another plan (the manifest or the recordings changed); give a "
                  "new --out or restore the manifest");
    return true;
  }
  io::check_output_folder(dir, policy);  // new, empty, or refused (a batch is never --force replaced)
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec))
    throw Error(dir.string(), "holds an earlier cropsight output that is not a batch; give a new --out");
  fs::create_directories(dir / "shards");
  io::write_file_atomic(dir / "plan.json", text);
  mark_batch_folder(dir);
  return false;
}

void mark_batch_folder(const fs::path& dir) { io::write_output_marker(dir, "batch"); }

}  // namespace cropsight::batch
