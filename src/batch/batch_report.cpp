// The batch's HTML summary (batch/batch_report.hpp).
#include "cropsight/batch/batch_report.hpp"

#include <cmath>
#include <cstdio>
#include <map>

#include "cropsight/io/files.hpp"
#include "cropsight/report/html_page.hpp"
#include "cropsight/report/svg_charts.hpp"
#include "fixed_text.hpp"

namespace cropsight::batch {

namespace {

using detail::fixed;

const std::vector<ShardRecord>& records_of(const BatchResult& r) {
  return r.plan.crop == "broccoli" ? r.merge.records : r.concat.records;
}

void add_summary(report::HtmlPage& page, const BatchResult& r) {
  const EngineReport& e = r.engine;
  double all_cpu_s = 0.0;  // every shard's, this run's and earlier runs'
  for (const ShardRecord& s : records_of(r)) all_cpu_s += s.cpu_s;
  page.section("Summary");
  std::vector<std::pair<std::string, std::string>> values{{"crop", r.plan.crop},
                                                          {"shards", std::to_string(e.planned)},
                                                          {"done before this run", std::to_string(e.already_done)},
                                                          {"ran", std::to_string(e.ran)},
                                                          {"failed", std::to_string(e.failed)},
                                                          {"resubmitted (Slurm)", std::to_string(e.resubmitted)},
                                                          {"frames processed", std::to_string(e.frames)},
                                                          {"CPU-hours (this run)", fixed(e.cpu_s / 3600.0, 4)},
                                                          {"CPU-hours (all shards)", fixed(all_cpu_s / 3600.0, 4)},
                                                          {"wall time (s)", fixed(e.wall_s, 1)}};
  if (r.plan.crop == "broccoli") {
    values.push_back({"merged heads", std::to_string(r.merge.heads_out)});
    values.push_back({"harvestable", std::to_string(r.merge.harvestable)});
  } else {
    values.push_back({"rows in " + r.concat.file, std::to_string(r.concat.rows)});
  }
  page.key_values(values);
  for (const std::string& line : e.errors) page.paragraph(line);
}

void add_map(report::HtmlPage& page, const BatchResult& r) {
  report::ScatterSeries ready{"harvestable", {}, {}, {}, "#2a7"}, other{"other heads", {}, {}, {}, "#c62"};
  for (const MergedHead& h : r.merge.heads) {
    report::ScatterSeries& s = h.harvestable ? ready : other;
    s.x.push_back(h.position.x());
    s.y.push_back(h.position.y());
    s.r.push_back(h.diameter_mm > 0 ? h.diameter_mm / 2000.0 : 0.03);  // unsized heads: a 6 cm dot
  }
  page.section("Merged field map");
  page.svg(report::svg_scatter_plot({ready, other}, {"heads in the field frame", "x (m)", "y (m)", 720, 420, true}),
           "circles: head diameter; field frame of the first recording");
}

void add_passes(report::HtmlPage& page, const BatchResult& r) {
  std::map<std::string, std::pair<int, int>> per_pass;  // heads, harvestable
  std::map<int, int> diameters;                         // 10 mm bins
  for (const MergedHead& h : r.merge.heads) {
    if (h.diameter_mm > 0) diameters[int(h.diameter_mm / 10) * 10] += 1;
    std::map<std::string, bool> seen;
    for (const Sighting& s : h.seen_by) seen[r.merge.map_passes.at(s.map)] = true;
    for (const auto& [pass, _] : seen) {
      per_pass[pass].first += 1;
      per_pass[pass].second += h.harvestable;
    }
  }
  std::vector<report::Bar> heads, ready, sizes, times;
  for (const auto& [pass, n] : per_pass) {
    heads.push_back({pass, double(n.first)});
    ready.push_back({pass, double(n.second)});
  }
  for (const auto& [bin, n] : diameters)
    sizes.push_back({std::to_string(bin) + "-" + std::to_string(bin + 10), double(n)});
  for (const ShardRecord& s : r.merge.records) times.push_back({s.name, s.wall_s});
  page.section("Passes");
  page.svg(report::svg_bar_chart(heads, "heads per pass", ""));
  page.svg(report::svg_bar_chart(ready, "harvestable heads per pass", ""));
  page.svg(report::svg_bar_chart(sizes, "merged heads per diameter (mm)", ""));
  page.section("Shards");
  page.svg(report::svg_bar_chart(times, "run time per shard", " s"));
}

// Potato, grape and seedling: per recording what its shards counted, and the shards' run times.
void add_recordings(report::HtmlPage& page, const BatchResult& r) {
  static const std::map<std::string, std::string> kItems{
      {"potato", "targets selected"}, {"grape", "bunches"}, {"seedling", "seedlings found"}};
  std::vector<report::Bar> detections, items, times;
  for (const RecordingSummary& s : r.concat.recordings) {
    detections.push_back({s.pass, double(s.detections)});
    items.push_back({s.pass, double(s.items)});
  }
  for (const ShardRecord& s : r.concat.records) times.push_back({s.name, s.wall_s});
  page.section("Recordings");
  page.paragraph("Every row is in " + r.concat.file + " and the sums per recording in passes.csv.");
  page.svg(report::svg_bar_chart(detections, "detections per recording", ""));
  page.svg(report::svg_bar_chart(items, kItems.at(r.plan.crop) + " per recording", ""));
  page.section("Shards");
  page.svg(report::svg_bar_chart(times, "run time per shard", " s"));
}

}  // namespace

std::string batch_report_html(const BatchResult& r) {
  report::HtmlPage page("cropsight batch");
  add_summary(page, r);
  if (r.merged && r.plan.crop == "broccoli") {
    add_map(page, r);
    add_passes(page, r);
  } else if (r.merged) {
    add_recordings(page, r);
  }
  return page.html();
}

void write_batch_report(const std::filesystem::path& path, const BatchResult& r) {
  io::write_file_atomic(path, batch_report_html(r));
}

}  // namespace cropsight::batch
