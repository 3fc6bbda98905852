// A tuning tool (not a test): measures how well a detector preset SEGMENTS the labelled heads of recorded
// sequences, independently of any classifier (the upper bound of AP50 recall). Used to tune the
// simulator's plant geometry and the OES/ORG presets on training seeds (docs/simulator.md,
// docs/experiments/2026-12-01-broccoli-oes-tuning.md). Run with
//
//   CROPSIGHT_SEG_PROBE=seq1[,seq2] [CROPSIGHT_SEG_PRESET=broccoli-oes-uk] [CROPSIGHT_SEG_FRAMES=10]
//   [CROPSIGHT_SEG_SET="key=value;key=value"] build/bin/broccoli_segmentation_probe
//
// Per labelled head instance (every head with a visible point in a frame, as AP counts them) it
// finds the cluster overlapping it most and prints how many reach IoU >= 0.5 ("found"), how many
// lie mostly inside a larger cluster ("merged": under half of that cluster is this head) and how
// many are broken or too small ("split / small"); the same for heads not cut by the image border
// with at least `min_size` visible points ("clear"), and for the heads with >= 300 visible points
// (the `ap50_visible` rule): found, merged, in pieces whose union would reach IoU 0.5, or neither
// (CROPSIGHT_SEG_VERBOSE=1 lists those with their edge-labelled pixels; CROPSIGHT_SEG_LIST=1 lists
// every such head with its outcome and best IoU, to compare two settings head by head). CROPSIGHT_SEG_MODEL=FILE
// also classifies the clusters and lists the misclassified ones; without CROPSIGHT_SEG_PRESET the
// detector then runs the model's recorded configuration, as `eval broccoli --model` does. CROPSIGHT_SEG_DUMP=DIR writes
// three frames (from CROPSIGHT_SEG_DUMP_FROM, default 1) as PNG: depth (turbo), cluster borders black, head outlines
// white, merged heads' and false positives' clusters magenta, with enlarged crops.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/organized_edges.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/detector.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"

using namespace cropsight;
using namespace cropsight::pipeline;
using namespace cropsight::pipeline::broccoli;

namespace {
std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}
void dump(const std::string& dir, int frame, const OrganizedCloud& cloud,
          std::span<const pipeline::broccoli::Candidate> cands, const std::vector<int>& merged_clusters,
          const std::vector<int>& merged_heads) {
  const int w = cloud.width, h = cloud.height;
  cv::Mat gray(h, w, CV_8UC1, cv::Scalar(0)), cluster(h, w, CV_32SC1, cv::Scalar(-1));
  for (int i = 0; i < w * h; ++i) {
    const float z = cloud.z[std::size_t(i)];
    if (std::isfinite(z))
      gray.at<std::uint8_t>(i / w, i % w) = std::uint8_t(std::clamp(255.0 * (1.0 - z) / 0.4, 1.0, 255.0));
  }
  cv::Mat out;
  cv::applyColorMap(gray, out, cv::COLORMAP_TURBO);
  for (int i = 0; i < w * h; ++i)
    if (!std::isfinite(cloud.z[std::size_t(i)])) out.at<cv::Vec3b>(i / w, i % w) = {60, 60, 60};
  for (std::size_t c = 0; c < cands.size(); ++c)
    for (int idx : cands[c].segment.indices) cluster.at<int>(idx / w, idx % w) = int(c);
  for (int c : merged_clusters)
    for (int idx : cands[std::size_t(c)].segment.indices) out.at<cv::Vec3b>(idx / w, idx % w) = {255, 0, 255};
  for (int v = 1; v < h; ++v)
    for (int u = 1; u < w; ++u) {
      const int c = cluster.at<int>(v, u);
      if (c != cluster.at<int>(v - 1, u) || c != cluster.at<int>(v, u - 1)) out.at<cv::Vec3b>(v, u) = {0, 0, 0};
      const auto l = cloud.labels[std::size_t(v * w + u)];
      if (l != cloud.labels[std::size_t(v * w + u - 1)] || l != cloud.labels[std::size_t((v - 1) * w + u)])
        out.at<cv::Vec3b>(v, u) = {255, 255, 255};
    }
  cv::imwrite(dir + "/probe-" + std::to_string(frame) + ".png", out);
  // Enlarged crops around the merged (or misclassified) clusters, and the colour image there.
  for (int c : merged_clusters) {
    const auto& b = cands[std::size_t(c)].segment.box;
    const int cu = b.x + b.width / 2, cv_ = b.y + b.height / 2, r = 45;
    const cv::Rect box = cv::Rect(cu - r, cv_ - r, 2 * r, 2 * r) & cv::Rect(0, 0, w, h);
    cv::Mat crop;
    cv::resize(out(box), crop, {}, 4, 4, cv::INTER_NEAREST);
    cv::imwrite(dir + "/probe-" + std::to_string(frame) + "-cluster" + std::to_string(c) + ".png", crop);
  }
  // Enlarged crops around the merged clusters' heads.
  for (std::size_t k = 0; k < merged_heads.size(); ++k) {
    long su = 0, sv = 0, n = 0;
    for (int i = 0; i < w * h; ++i)
      if (cloud.labels[std::size_t(i)] == merged_heads[k]) su += i % w, sv += i / w, ++n;
    if (!n) continue;
    const int cu = int(su / n), cv_ = int(sv / n), r = 45;
    const cv::Rect box = cv::Rect(cu - r, cv_ - r, 2 * r, 2 * r) & cv::Rect(0, 0, w, h);
    cv::Mat crop;
    cv::resize(out(box), crop, {}, 4, 4, cv::INTER_NEAREST);
    cv::imwrite(dir + "/probe-" + std::to_string(frame) + "-head" + std::to_string(merged_heads[k]) + ".png", crop);
  }
}
}  // namespace

// Long on purpose: a tuning probe whose per-head counters are filled and printed together.
int probe() {
  const char* seqs = std::getenv("CROPSIGHT_SEG_PROBE");
  if (!seqs) {
    std::fprintf(stderr, "broccoli_segmentation_probe: set CROPSIGHT_SEG_PROBE=seq[,seq] (see the file's comment)\n");
    return 2;
  }
  const char* preset_env = std::getenv("CROPSIGHT_SEG_PRESET");
  const char* model_env = std::getenv("CROPSIGHT_SEG_MODEL");
  const int max_frames = std::getenv("CROPSIGHT_SEG_FRAMES") ? std::atoi(std::getenv("CROPSIGHT_SEG_FRAMES")) : 10;
  ConfigMap overrides;
  if (const char* set = std::getenv("CROPSIGHT_SEG_SET"))
    for (const auto& kv : split(set, ';')) {
      const auto eq = kv.find('=');
      if (eq == std::string::npos) throw Error("CROPSIGHT_SEG_SET", "expected key=value, got '" + kv + "'");
      overrides[kv.substr(0, eq)] = kv.substr(eq + 1);
    }
  // With a model and no preset, the detector runs the model's recorded configuration (as `eval
  // broccoli --model` does); otherwise the preset's (default broccoli-oes-uk). CROPSIGHT_SEG_SET on top.
  std::shared_ptr<learning::Model> model;
  if (model_env) model = std::make_shared<learning::Model>(learning::load_model(model_env));
  const std::string preset = preset_env ? preset_env : model ? std::string(model_env) : "broccoli-oes-uk";
  pipeline::broccoli::DetectorConfig cfg;
  if (model && !preset_env) {
    cfg = pipeline::broccoli::config_for_model(*model, overrides, model_env, "CROPSIGHT_SEG_SET").detector;
  } else {
    ConfigMap values = io::load_config_map(io::find_preset(preset));
    for (const auto& [k, v] : overrides) values[k] = v;
    apply_config(cfg, values, preset);
  }
  cfg.validate(preset);
  const int min_size = cfg.pipeline == pipeline::broccoli::Variant::oes   ? cfg.oes.min_size
                       : cfg.pipeline == pipeline::broccoli::Variant::org ? cfg.org.min_size
                                                                          : cfg.fec.min_size;
  pipeline::broccoli::Detector det(cfg);
  // With CROPSIGHT_SEG_MODEL, also lists the misclassified clusters (size, share of their majority head).
  if (model) det.set_model(model, model_env);
  long all = 0, found = 0, merged = 0, clear = 0, clear_found = 0, clear_merged = 0, clear_split = 0, clusters = 0,
       frames = 0;
  // Heads with >= 300 visible points (the `ap50_visible` rule) that are not found: merged, in
  // pieces whose union would reach IoU 0.5 (each piece mostly this head), or neither.
  long vis = 0, vis_found = 0, vis_merged = 0, vis_union = 0, vis_other = 0;
  std::vector<TruthInstance> truth;
  // The dump folder is written whole at the end, by the one output rule (a rerun replaces only an
  // earlier dump; never a folder of other files, never an input).
  std::optional<io::OutputFolder> dump_out;
  if (const char* d = std::getenv("CROPSIGHT_SEG_DUMP")) {
    std::vector<std::filesystem::path> inputs;
    for (const auto& dir : split(seqs, ',')) inputs.emplace_back(dir);
    dump_out.emplace(d, io::OutputPolicy{"broccoli_segmentation_probe", true, inputs});
  }
  for (const auto& dir : split(seqs, ',')) {
    io::SequenceReader reader(dir);
    for (int i = 0; i < std::min(max_frames, reader.size()); ++i) {
      const auto cands = det.process(reader.read(i));
      ++frames;
      clusters += long(cands.size());
      std::vector<int> fp_clusters;
      if (det.has_model())
        for (const auto& c : cands) {
          // Majority head of the cluster, whatever its share (truth.head_id is 0 below one half).
          const auto any = cluster_truth(c.segment.indices, det.cloud().labels, 0.0f);
          const bool is_head = cluster_truth(c.segment.indices, det.cloud().labels).head_id != 0;
          if (c.head && !is_head) fp_clusters.push_back(int(&c - cands.data()));
          if (c.head != is_head) {
            std::size_t with_normal = 0;
            for (int idx : c.segment.indices) with_normal += std::isfinite(det.cloud().nx[std::size_t(idx)]);
            std::printf(
                "%s frame %ld cluster %zu points (%zu with a normal), majority head %d holds %.2f of it, "
                "score %.3f\n",
                c.head ? "FP" : "FN", frames, c.segment.indices.size(), with_normal, any.head_id, any.fraction,
                c.score);
          }
        }
      truth_instances(det.cloud(), 1, truth);
      const auto& labels = det.cloud().labels;
      std::vector<int> merged_clusters = fp_clusters, merged_heads;  // false positives drawn as merged
      for (const auto& t : truth) {
        // The cluster holding most of this head's points, and the IoU of the best cluster.
        double best_iou = 0.0, best_overlap = 0.0, share_of_cluster = 0.0;
        long union_inter = 0, union_size = 0;
        int best_cluster = -1;
        for (std::size_t ci = 0; ci < cands.size(); ++ci) {
          const auto& c = cands[ci];
          long inter = 0;
          for (int idx : c.segment.indices) inter += labels[std::size_t(idx)] == t.id;
          if (inter == 0) continue;
          const double iou = double(inter) / double(c.segment.indices.size() + t.indices.size() - inter);
          if (2 * inter > long(c.segment.indices.size()))
            union_inter += inter, union_size += long(c.segment.indices.size());
          best_iou = std::max(best_iou, iou);
          if (inter > best_overlap) {
            best_overlap = double(inter);
            share_of_cluster = double(inter) / double(c.segment.indices.size());
            best_cluster = int(ci);
          }
        }
        const bool ok = best_iou >= 0.5;
        const bool merge = !ok && best_overlap >= 0.5 * double(t.indices.size()) && share_of_cluster < 0.5;
        // Neither: the head is in pieces, or its best cluster is below min_size (or it has none).
        if (!t.cut_by_border && int(t.indices.size()) >= min_size && !ok && !merge) ++clear_split;
        if (t.indices.size() >= 300) {
          ++vis;
          const double union_iou =
              union_size ? double(union_inter) / double(union_size + long(t.indices.size()) - union_inter) : 0.0;
          if (ok)
            ++vis_found;
          else if (merge)
            ++vis_merged;
          else if (union_iou >= 0.5)
            ++vis_union;
          else {
            ++vis_other;
            merged_heads.push_back(t.id);  // cropped in the dump too
            if (std::getenv("CROPSIGHT_SEG_VERBOSE")) {
              const auto edges = geometry::detect_organized_edges(det.cloud(), cfg.edges);
              int e[4] = {0, 0, 0, 0};
              for (int idx : t.indices)
                for (int b = 0; b < 4; ++b) e[b] += (edges[std::size_t(idx)] >> b) & 1;
              std::printf(
                  "MISS frame %ld head %d pts %zu border %d best_iou %.2f union_iou %.2f best_cluster %d "
                  "overlap %.0f | edge px nan %d occluding %d occluded %d\n",
                  frames, t.id, t.indices.size(), int(t.cut_by_border), best_iou, union_iou,
                  best_cluster >= 0 ? int(cands[std::size_t(best_cluster)].segment.indices.size()) : 0, best_overlap,
                  e[0], e[1], e[2]);
            }
          }
        }
        if (std::getenv("CROPSIGHT_SEG_LIST") && t.indices.size() >= 300)
          std::printf("HEAD %s %ld %d %s %.2f\n", dir.c_str(), frames, t.id,
                      ok      ? "found"
                      : merge ? "merged"
                              : "other",
                      best_iou);
        ++all;
        found += ok;
        merged += merge;
        if (merge) merged_clusters.push_back(best_cluster), merged_heads.push_back(t.id);
        if (!t.cut_by_border && int(t.indices.size()) >= min_size) {
          ++clear;
          clear_found += ok;
          clear_merged += merge;
        }
      }
      const long dump_from =
          std::getenv("CROPSIGHT_SEG_DUMP_FROM") ? std::atol(std::getenv("CROPSIGHT_SEG_DUMP_FROM")) : 1;
      if (dump_out && frames >= dump_from && frames < dump_from + 3)
        dump(dump_out->path().string(), int(frames), det.cloud(), cands, merged_clusters, merged_heads);
    }
  }
  if (dump_out) dump_out->commit("probe pictures");
  std::printf(
      "SEGPROBE preset=%s frames=%ld clusters/frame=%.1f heads: found %ld / %ld (%.3f), merged %ld | "
      "clear heads (in view, >= %d points): found %ld / %ld (%.3f), merged %ld, split/small %ld\n",
      preset.c_str(), frames, frames ? double(clusters) / double(frames) : 0.0, found, all,
      all ? double(found) / double(all) : 0.0, merged, min_size, clear_found, clear,
      clear ? double(clear_found) / double(clear) : 0.0, clear_merged, clear_split);
  std::printf(
      "SEGPROBE visible (>= 300 points): %ld, found %ld, merged %ld, pieces whose union reaches 0.5 %ld, other %ld\n",
      vis, vis_found, vis_merged, vis_union, vis_other);
  return 0;
}

int main() {
  try {
    return probe();
  } catch (const Error& e) {
    std::fprintf(stderr, "broccoli_segmentation_probe: %s\n", e.what());
    return 2;
  }
}
