// The merge step of a batch (batch/batch_merge.hpp).
#include "cropsight/batch/batch_merge.hpp"

#include <map>
#include <memory>
#include <set>

#include "cropsight/batch/field_merge.hpp"
#include "cropsight/batch/field_outputs.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/tracking/field_map_io.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

std::optional<io::GeoOrigin> check_geo_origins(const BatchPlan& plan) {
  std::optional<io::GeoOrigin> first;
  std::set<fs::path> with, without;
  for (const Shard& s : plan.shards) {
    const auto g = io::read_sequence_geo_origin(s.sequence);
    (g ? with : without).insert(s.sequence);
    if (g && !first) first = g;
  }
  if (!with.empty() && !without.empty())
    throw Error(without.begin()->string(), "has no geo_origin.yaml while " + with.begin()->string() +
                                               " has one (a merged map needs all recordings geo-referenced or none)");
  return first;
}

MergeSummary merge_maps(const std::vector<MapInput>& inputs, const MergeRule& rule, const fs::path& out_dir,
                        double row_gap_m, std::vector<ShardRecord> records) {
  MergeSummary sum;
  sum.records = std::move(records);
  std::optional<io::GeoReference> common;
  std::map<fs::path, std::unique_ptr<io::GeoReference>> own;  // each recording's own field frame
  std::size_t with_origin = 0;
  for (const MapInput& in : inputs) {
    if (in.sequence.empty()) continue;
    const auto g = io::read_sequence_geo_origin(in.sequence);
    if (!g) continue;
    ++with_origin;
    if (!common) common.emplace(*g);
    if (!own.count(in.sequence)) own[in.sequence] = std::make_unique<io::GeoReference>(*g);
  }
  if (with_origin != 0 && with_origin != inputs.size())
    throw Error("merge", "only " + std::to_string(with_origin) + " of " + std::to_string(inputs.size()) +
                             " maps come from geo-referenced recordings (all or none)");
  std::vector<PassMap> maps;
  std::set<std::string> passes;
  for (const MapInput& in : inputs) {
    PassMap m{in.pass, in.name, tracking::read_field_map(in.map)};
    if (common) {
      const io::GeoReference& from = *own.at(in.sequence);
      for (auto& h : m.heads) h.position = common->to_field(from.to_wgs84(h.position));
    }
    sum.heads_in += m.heads.size();
    passes.insert(in.pass);
    sum.map_passes.push_back(in.pass);
    maps.push_back(std::move(m));
  }
  const Stopwatch clock;
  auto heads = merge_field_maps(maps, rule);
  assign_rows(heads, row_gap_m);
  sum.seconds = clock.seconds();
  sum.maps = maps.size();
  sum.passes = passes.size();
  sum.heads_out = heads.size();
  for (const auto& h : heads) sum.harvestable += h.harvestable;
  sum.geo = common.has_value();
  io::write_file_atomic(out_dir / "field-map.csv", merged_map_csv(heads, maps, common ? &*common : nullptr));
  io::write_file_atomic(out_dir / "passes.csv", passes_csv(heads, maps, sum.records));
  io::write_file_atomic(out_dir / "rows.csv", rows_csv(heads, maps));
  if (common) io::write_file_atomic(out_dir / "field-map.geojson", merged_map_geojson(heads, maps, *common));
  sum.heads = std::move(heads);
  return sum;
}

MergeSummary merge_batch(const BatchPlan& plan, const fs::path& batch_dir, double row_gap_m) {
  std::vector<MapInput> inputs;
  std::vector<ShardRecord> records;
  for (const Shard& s : plan.shards) {
    const fs::path folder = shard_folder(batch_dir, s);
    if (!shard_done(batch_dir, s)) throw Error(folder.string(), "shard not done; rerun the batch to finish it");
    records.push_back(read_shard_record(folder / "shard.json"));
    inputs.push_back({s.pass, s.name, folder / "field-map.csv", s.sequence});
  }
  return merge_maps(inputs, plan.merge, batch_dir, row_gap_m, std::move(records));
}

}  // namespace cropsight::batch
