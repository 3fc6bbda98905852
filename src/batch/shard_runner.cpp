// Running one shard into its own folder, atomically (batch/shard_runner.hpp).
#include "cropsight/batch/shard_runner.hpp"

#include <unistd.h>

#include <ctime>
#include <nlohmann/json.hpp>

#include "cropsight/batch/crop_shards.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// CPU seconds of the calling thread: a local batch runs one shard per worker thread.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

std::string host_name() {
  char buf[256] = {};
  gethostname(buf, sizeof buf - 1);
  return buf;
}

json record_json(const ShardRecord& r) {
  return {{"name", r.name},   {"pass", r.pass},     {"frames", r.frames}, {"detections", r.detections},
          {"items", r.items}, {"wall_s", r.wall_s}, {"cpu_s", r.cpu_s},   {"host", r.host}};
}

}  // namespace

fs::path shard_folder(const fs::path& batch_dir, const Shard& shard) { return batch_dir / "shards" / shard.name; }

bool shard_done(const fs::path& batch_dir, const Shard& shard) {
  std::error_code ec;
  return fs::is_regular_file(shard_folder(batch_dir, shard) / "shard.json", ec);
}

ShardRecord run_shard(const BatchPlan& plan, std::size_t index, const fs::path& batch_dir) {
  const Shard& shard = plan.shards.at(index);
  const Stopwatch clock;
  const double cpu0 = thread_cpu_seconds();
  const fs::path folder = shard_folder(batch_dir, shard);
  fs::create_directories(folder.parent_path());
  io::TempDirectory tmp(folder);  // removes what killed attempts left beside it
  const ShardCounts counts = run_crop_shard(plan.crop, plan.spec, shard, tmp.path());
  ShardRecord r{shard.name, shard.pass, counts.frames, counts.detections, counts.items};
  r.cpu_s = thread_cpu_seconds() - cpu0;
  r.wall_s = clock.seconds();
  r.host = host_name();
  io::write_file_atomic(tmp.path() / "shard.json", record_json(r).dump() + "\n");  // last: the done marker
  tmp.commit("shard " + shard.name);
  return r;
}

ShardRecord read_shard_record(const fs::path& path) {
  try {
    const json j = json::parse(io::read_file(path));
    // "heads": the key of batches written before other crops could run.
    const json& items = j.contains("items") ? j.at("items") : j.at("heads");
    return {j.at("name"), j.at("pass"),   j.at("frames"), j.at("detections"),
            items,        j.at("wall_s"), j.at("cpu_s"),  j.at("host")};
  } catch (const json::exception& e) {
    throw Error(path.string(), std::string("not a shard record: ") + e.what());
  }
}

}  // namespace cropsight::batch
