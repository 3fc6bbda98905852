// A whole batch: plan, checks, engine, merge, summary (batch/batch_run.hpp).
#include "cropsight/batch/batch_run.hpp"

#include <nlohmann/json.hpp>

#include "cropsight/batch/batch_folder.hpp"
#include "cropsight/batch/batch_report.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

BatchResult run_batch(const Manifest& manifest, const fs::path& dir, const BatchOptions& options, const BatchLog& log) {
  if (options.engine != "local" && options.engine != "slurm")
    throw Error("--engine", "must be local or slurm, got '" + options.engine + "'");
  BatchResult result;
  result.plan = plan_batch(manifest);
  check_geo_origins(result.plan);  // a mixed batch must fail before submission, not at the merge
  result.resumed = open_batch_folder(dir, result.plan, options.force);
  if (options.engine == "local")
    result.engine = run_local(result.plan, dir, options.workers, log);
  else
    result.engine = run_slurm(result.plan, dir, options.slurm, log);
  mark_batch_folder(dir);
  if (result.engine.failed == 0) {
    if (result.plan.crop == "broccoli")
      result.merge = merge_batch(result.plan, dir, options.row_gap_m);
    else
      result.concat = concat_batch(result.plan, dir);
    result.merged = true;
  }
  io::write_file_atomic(dir / "summary.json", batch_summary_json(result));
  write_batch_report(dir / "report.html", result);
  mark_batch_folder(dir);
  return result;
}

std::string batch_summary_json(const BatchResult& r) {
  const EngineReport& e = r.engine;
  nlohmann::json j{{"crop", r.plan.crop},
                   {"shards", e.planned},
                   {"already_done", e.already_done},
                   {"ran", e.ran},
                   {"failed", e.failed},
                   {"resubmitted", e.resubmitted},
                   {"frames", e.frames},
                   {"cpu_hours", e.cpu_s / 3600.0},
                   {"wall_s", e.wall_s},
                   {"resumed", r.resumed},
                   {"jobs", e.job_ids},
                   {"errors", e.errors},
                   {"merged", r.merged}};
  if (r.merged && r.plan.crop != "broccoli") {
    nlohmann::json per = nlohmann::json::array();
    for (const RecordingSummary& s : r.concat.recordings)
      per.push_back({{"recording", s.pass}, {"frames", s.frames}, {"detections", s.detections}, {"items", s.items}});
    j["concat"] = {{"file", r.concat.file}, {"rows", r.concat.rows}, {"recordings", per}};
  } else if (r.merged)
    j["merge"] = {{"maps", r.merge.maps},       {"passes", r.merge.passes},           {"heads_in", r.merge.heads_in},
                  {"heads", r.merge.heads_out}, {"harvestable", r.merge.harvestable}, {"geo", r.merge.geo},
                  {"seconds", r.merge.seconds}};
  return j.dump() + "\n";
}

}  // namespace cropsight::batch
