// Shard planning and plan.json (batch/plan.hpp).
#include "cropsight/batch/plan.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cropsight/batch/crop_shards.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<Shard> plan_recording(const fs::path& sequence, int frames, const ShardingOptions& o) {
  std::vector<Shard> out;
  const std::string pass = sequence.filename().string();
  if (o.frames_per_shard <= 0 || frames <= o.frames_per_shard) {
    out.push_back({pass, pass, sequence, 0, frames, 0, frames});
    return out;
  }
  for (int a = 0; a < frames; a += o.frames_per_shard) {
    const int b = std::min(frames, a + o.frames_per_shard);
    char name[32];
    std::snprintf(name, sizeof name, "-f%06d", a);  // zero-padded: names sort in frame order
    out.push_back(
        {pass + name, pass, sequence, std::max(0, a - o.overlap_frames), std::min(frames, b + o.overlap_frames), a, b});
  }
  return out;
}

BatchPlan plan_batch(const Manifest& m) {
  BatchPlan plan;
  plan.manifest = m.file;
  plan.crop = m.crop;
  plan.spec = m.spec;
  plan.slurm = m.slurm;
  if (m.crop == "broccoli") {
    const auto pipe = pipeline::broccoli::make_pipeline(m.spec);
    plan.merge = {pipe->config().tracking.association_radius_m, pipe->config().sizing.market_min_mm,
                  pipe->config().sizing.market_max_mm};
  }
  for (const fs::path& rec : m.recordings)
    for (Shard& s : plan_recording(rec, recording_frames(m.crop, rec), m.sharding)) plan.shards.push_back(std::move(s));
  std::sort(plan.shards.begin(), plan.shards.end(), [](const Shard& a, const Shard& b) { return a.name < b.name; });
  return plan;
}

std::string plan_json(const BatchPlan& p) {
  json shards = json::array();
  for (const Shard& s : p.shards)
    shards.push_back({{"name", s.name},
                      {"pass", s.pass},
                      {"sequence", s.sequence.string()},
                      {"frames", {s.first_frame, s.end_frame}},
                      {"owned_frames", {s.own_first, s.own_end}}});
  const json j{
      {"manifest", p.manifest.string()},
      {"crop", p.crop},
      {"pipeline",
       {{"preset", p.spec.preset}, {"model", p.spec.model}, {"sets", p.spec.sets}, {"detector", p.spec.detector}}},
      {"merge",
       {{"association_radius_m", p.merge.association_radius_m},
        {"market_min_mm", p.merge.market_min_mm},
        {"market_max_mm", p.merge.market_max_mm}}},
      {"slurm",
       {{"partition", p.slurm.partition},
        {"account", p.slurm.account},
        {"time", p.slurm.time},
        {"mem", p.slurm.mem},
        {"cpus_per_task", p.slurm.cpus_per_task},
        {"max_retries", p.slurm.max_retries},
        {"max_parallel", p.slurm.max_parallel}}},
      {"shards", shards}};
  return j.dump(1) + "\n";
}

BatchPlan read_plan(const fs::path& path) {
  BatchPlan p;
  try {
    const json j = json::parse(io::read_file(path));
    p.manifest = j.at("manifest").get<std::string>();
    p.crop = j.at("crop").get<std::string>();
    const json& pipe = j.at("pipeline");
    p.spec.preset = pipe.at("preset").get<std::string>();
    p.spec.model = pipe.at("model").get<std::string>();
    p.spec.sets = pipe.at("sets").get<std::vector<std::string>>();
    p.spec.detector = pipe.value("detector", std::string());  // absent in plans of broccoli-only batches
    const json& merge = j.at("merge");
    p.merge = {merge.at("association_radius_m").get<double>(), merge.at("market_min_mm").get<double>(),
               merge.at("market_max_mm").get<double>()};
    const json& s = j.at("slurm");
    p.slurm = {s.at("partition"),     s.at("account"),     s.at("time"),        s.at("mem"),
               s.at("cpus_per_task"), s.at("max_retries"), s.at("max_parallel")};
    for (const json& e : j.at("shards"))
      p.shards.push_back({e.at("name"), e.at("pass"), e.at("sequence").get<std::string>(), e.at("frames").at(0),
                          e.at("frames").at(1), e.at("owned_frames").at(0), e.at("owned_frames").at(1)});
  } catch (const json::exception& e) {
    throw Error(path.string(), std::string("not a batch plan: ") + e.what());
  }
  return p;
}

}  // namespace cropsight::batch
