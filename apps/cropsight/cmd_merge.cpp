// cropsight merge: field maps of several passes (detect broccoli --track --map) into one map, by
// the temporal filter's association rule (batch/field_merge.hpp); geo-referenced when --data names
// the recordings and they carry geo_origin.yaml. `cropsight batch` ends with the same merge.
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/batch/batch_merge.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/tracking/temporal_filter.hpp"

namespace cropsight::cli {

namespace merge_cmd {
struct MergeCliOptions {
  std::string maps, data, out;
  double radius_m = tracking::TemporalFilterConfig{}.association_radius_m;
  double row_gap_m = 0.3;
  bool force = false;
  CommonOptions common;  // --json only
};

void run(const MergeCliOptions& o) {
  const auto maps = split_list(o.maps, "--maps");
  const auto data = o.data.empty() ? std::vector<std::string>(maps.size()) : split_list(o.data, "--data");
  if (data.size() != maps.size())
    throw Error("--data", "needs one recording per map (" + std::to_string(maps.size()) + ")");
  if (!(o.radius_m > 0)) throw Error("--radius", "must be positive");
  std::vector<std::string> inputs = maps;
  inputs.insert(inputs.end(), data.begin(), data.end());
  io::OutputFolder out(o.out, output_policy("merge", o.force, inputs));
  std::vector<batch::MapInput> in;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    // A map's pass is its recording's name when given, else the map's own file name.
    const std::string pass = data[i].empty() ? std::filesystem::path(maps[i]).stem().string()
                                             : std::filesystem::path(data[i]).filename().string();
    in.push_back({pass, pass + "." + std::to_string(i + 1), maps[i], data[i]});
  }
  batch::MergeRule rule;
  rule.association_radius_m = o.radius_m;
  const batch::MergeSummary s = batch::merge_maps(in, rule, out.path(), o.row_gap_m);
  out.commit("merged map");
  if (o.common.json)
    print_json({{"maps", s.maps},
                {"heads_in", s.heads_in},
                {"heads", s.heads_out},
                {"harvestable", s.harvestable},
                {"geo", s.geo},
                {"out", o.out}});
  else
    std::printf("merged %zu maps: %zu heads into %zu (%zu harvestable)%s; wrote %s\n", s.maps, s.heads_in, s.heads_out,
                s.harvestable, s.geo ? " with WGS84" : "", o.out.c_str());
}
}  // namespace merge_cmd

void add_merge(CLI::App& app) {
  using namespace merge_cmd;
  auto o = std::make_shared<MergeCliOptions>();
  auto* cmd = app.add_subcommand("merge", "Merge the field maps of several passes into one map");
  cmd->add_option("--maps", o->maps, "Field maps, comma-separated (detect broccoli --track --map)")->required();
  cmd->add_option("--data", o->data, "Their recordings, comma-separated, same order (for geo_origin.yaml)");
  cmd->add_option("--out", o->out, "New folder: field-map.csv, passes.csv, rows.csv[, field-map.geojson]")->required();
  cmd->add_option("--radius", o->radius_m, "m; association radius (the temporal filter's, 0.05)");
  cmd->add_option("--row-gap", o->row_gap_m, "m; a gap across the rows larger than this starts a new row")
      ->default_val(0.3);
  add_force_flag(cmd, o->force);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
