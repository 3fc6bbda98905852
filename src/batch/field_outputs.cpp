// Text of the merged map's files (batch/field_outputs.hpp). Fixed formats: equal maps, equal bytes.
#include "cropsight/batch/field_outputs.hpp"

#include "fixed_text.hpp"

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

namespace cropsight::batch {

namespace {

std::set<std::string> passes_of(const MergedHead& h, const std::vector<PassMap>& maps) {
  std::set<std::string> out;
  for (const Sighting& s : h.seen_by) out.insert(maps[s.map].pass);
  return out;
}

std::string seen_by_text(const MergedHead& h, const std::vector<PassMap>& maps) {
  std::string out;
  char buf[160];
  for (const Sighting& s : h.seen_by) {
    std::snprintf(buf, sizeof buf, "%s%s#%d:%d-%d", out.empty() ? "" : " ", maps[s.map].shard.c_str(), s.head_id,
                  s.first_frame, s.last_frame);
    out += buf;
  }
  return out;
}

using detail::fixed;

}  // namespace

std::string merged_map_csv(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps,
                           const io::GeoReference* geo) {
  std::string out = "id,x_m,y_m,z_m,";
  if (geo) out += "latitude_deg,longitude_deg,altitude_m,";
  out += "diameter_mm,bbox_diameter_mm,hull_diameter_mm,frames_seen,passes,row,harvestable,seen_by\n";
  for (const MergedHead& h : heads) {
    out += std::to_string(h.id) + "," + fixed(h.position.x(), 4) + "," + fixed(h.position.y(), 4) + "," +
           fixed(h.position.z(), 4) + ",";
    if (geo) {
      const io::Wgs84 w = geo->to_wgs84(h.position);
      out += fixed(w.latitude_deg, 9) + "," + fixed(w.longitude_deg, 9) + "," + fixed(w.altitude_m, 3) + ",";
    }
    out += fixed(h.diameter_mm, 1) + "," + fixed(h.bbox_mm, 1) + "," + fixed(h.hull_mm, 1) + "," +
           std::to_string(h.frames_seen) + "," + std::to_string(passes_of(h, maps).size()) + "," +
           std::to_string(h.row) + "," + (h.harvestable ? "1" : "0") + "," + seen_by_text(h, maps) + "\n";
  }
  return out;
}

std::string merged_map_geojson(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps,
                               const io::GeoReference& geo) {
  // Written by hand, not by nlohmann's dump, to fix the digits: 1e-9 degree is 0.1 mm.
  std::string out = "{\"type\":\"FeatureCollection\",\"features\":[\n";
  for (std::size_t i = 0; i < heads.size(); ++i) {
    const MergedHead& h = heads[i];
    const io::Wgs84 w = geo.to_wgs84(h.position);
    const nlohmann::json props{{"id", h.id},
                               {"diameter_mm", std::stod(fixed(h.diameter_mm, 1))},
                               {"frames_seen", h.frames_seen},
                               {"passes", passes_of(h, maps).size()},
                               {"row", h.row},
                               {"harvestable", h.harvestable},
                               {"x_m", std::stod(fixed(h.position.x(), 4))},
                               {"y_m", std::stod(fixed(h.position.y(), 4))},
                               {"seen_by", seen_by_text(h, maps)}};
    out += "{\"type\":\"Feature\",\"geometry\":{\"type\":\"Point\",\"coordinates\":[" + fixed(w.longitude_deg, 9) +
           "," + fixed(w.latitude_deg, 9) + "," + fixed(w.altitude_m, 3) + "]},\"properties\":" + props.dump() + "}" +
           (i + 1 < heads.size() ? ",\n" : "\n");
  }
  return out + "]}\n";
}

std::string passes_csv(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps,
                       const std::vector<ShardRecord>& records) {
  struct PassStats {
    int shards = 0, frames = 0, heads = 0, harvestable = 0, shared = 0, sized = 0;
    double diameter_sum = 0;
  };
  std::map<std::string, PassStats> stats;
  for (const ShardRecord& r : records) {
    stats[r.pass].shards += 1;
    stats[r.pass].frames += r.frames;
  }
  for (const MergedHead& h : heads) {
    const auto passes = passes_of(h, maps);
    for (const std::string& p : passes) {
      PassStats& s = stats[p];
      s.heads += 1;
      s.harvestable += h.harvestable;
      s.shared += passes.size() > 1;
      if (h.sized_frames > 0) s.sized += 1, s.diameter_sum += h.diameter_mm;
    }
  }
  std::string out = "pass,shards,frames,heads,harvestable,shared_heads,mean_diameter_mm\n";
  for (const auto& [pass, s] : stats)
    out += pass + "," + std::to_string(s.shards) + "," + std::to_string(s.frames) + "," + std::to_string(s.heads) +
           "," + std::to_string(s.harvestable) + "," + std::to_string(s.shared) + "," +
           fixed(s.sized ? s.diameter_sum / s.sized : 0.0, 1) + "\n";
  return out;
}

std::string rows_csv(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps) {
  struct RowStats {
    int heads = 0, harvestable = 0, sized = 0;
    double y_sum = 0, diameter_sum = 0;
    std::set<std::string> passes;
  };
  std::map<int, RowStats> rows;
  for (const MergedHead& h : heads) {
    RowStats& r = rows[h.row];
    r.heads += 1;
    r.harvestable += h.harvestable;
    r.y_sum += h.position.y();
    if (h.sized_frames > 0) r.sized += 1, r.diameter_sum += h.diameter_mm;
    for (const std::string& p : passes_of(h, maps)) r.passes.insert(p);
  }
  std::string out = "row,y_m,heads,harvestable,passes,mean_diameter_mm\n";
  for (const auto& [row, r] : rows)
    out += std::to_string(row) + "," + fixed(r.y_sum / r.heads, 3) + "," + std::to_string(r.heads) + "," +
           std::to_string(r.harvestable) + "," + std::to_string(r.passes.size()) + "," +
           fixed(r.sized ? r.diameter_sum / r.sized : 0.0, 1) + "\n";
  return out;
}

}  // namespace cropsight::batch
