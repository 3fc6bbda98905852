// Concatenated outputs of potato, grape and seedling batches (batch/batch_concat.hpp).
#include "cropsight/batch/batch_concat.hpp"

#include <map>

#include "cropsight/batch/crop_shards.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "fixed_text.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

namespace {

// Appends the data lines of one shard's file (its header checked against the first shard's).
std::size_t append_rows(const fs::path& file, const std::string& prefix, std::string& header, std::string& out) {
  const std::string text = io::read_file(file);
  const std::size_t eol = text.find('\n');
  if (eol == std::string::npos) throw Error(file.string(), "no header line");
  const std::string head = text.substr(0, eol);
  if (header.empty()) header = head;
  if (head != header) throw Error(file.string(), "header differs from the other shards' ('" + header + "')");
  std::size_t rows = 0;
  for (std::size_t at = eol + 1; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    if (end > at) out += prefix + text.substr(at, end - at) + "\n", ++rows;
    at = end + 1;
  }
  return rows;
}

std::string passes_csv(const std::vector<RecordingSummary>& recordings) {
  std::string out = "recording,shards,frames_processed,detections,items,cpu_s\n";
  for (const RecordingSummary& r : recordings)
    out += r.pass + "," + std::to_string(r.shards) + "," + std::to_string(r.frames) + "," +
           std::to_string(r.detections) + "," + std::to_string(r.items) + "," + detail::fixed(r.cpu_s, 3) + "\n";
  return out;
}

}  // namespace

ConcatSummary concat_batch(const BatchPlan& plan, const fs::path& batch_dir) {
  ConcatSummary sum;
  sum.file = shard_output_file(plan.crop);
  std::string header, rows;
  std::map<std::string, RecordingSummary> per;
  for (const Shard& s : plan.shards) {
    const fs::path folder = shard_folder(batch_dir, s);
    if (!shard_done(batch_dir, s)) throw Error(folder.string(), "shard not done; rerun the batch to finish it");
    const ShardRecord rec = read_shard_record(folder / "shard.json");
    sum.rows += append_rows(folder / sum.file, s.pass + "," + s.name + ",", header, rows);
    RecordingSummary& r = per[s.pass];
    r.pass = s.pass;
    r.shards += 1;
    r.frames += rec.frames;
    r.detections += rec.detections;
    r.items += rec.items;
    r.cpu_s += rec.cpu_s;
    sum.records.push_back(rec);
  }
  for (auto& [_, r] : per) sum.recordings.push_back(r);
  io::write_file_atomic(batch_dir / sum.file, "recording,shard," + header + "\n" + rows);
  io::write_file_atomic(batch_dir / "passes.csv", passes_csv(sum.recordings));
  return sum;
}

}  // namespace cropsight::batch
