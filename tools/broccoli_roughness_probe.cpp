// A tuning tool (not a test): can surface roughness tell a head from the leaves it lies in? For the
// clusters a detector leaves unaccepted (rejected ones of detection.split_min_points or more, oversized regions),
// it compares the curvature (the integral normals' λ0 / trace) of their head pixels with that of the
// rest and prints the quantiles and the AUC (probability that a head pixel is rougher). Run as
//
//   build/bin/broccoli_roughness_probe MODEL.json seq1[,seq2] [key=value ...]
//
// (the model's recorded configuration, the key=value overrides on top; e.g. oes.max_size=200000 keeps
// the regions OES would drop). docs/experiments/2026-12-06-broccoli-split-accepted-field-maps.md
// ("Fields drawn to the description") has the result that ended this idea (AUC 0.64).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "broccoli_probe_args.hpp"
#include "cropsight/io/sequence.hpp"

using namespace cropsight;
using namespace cropsight::pipeline;

int main(int argc, char** argv) {
  const auto args = tools::parse_probe_args("broccoli_roughness_probe", argc, argv);
  if (!args) return 2;
  const pipeline::broccoli::DetectorConfig& cfg = args->config;
  pipeline::broccoli::Detector det(cfg);
  det.set_model(args->model);
  std::vector<float> head, other;
  for (const std::string& dir : args->sequences) {
    io::SequenceReader reader(dir);
    for (int i = 0; i < reader.size(); ++i) {
      const auto cands = det.process(reader.read(i));
      const auto& c = det.cloud();
      for (const auto& k : cands) {
        if (!tools::unaccepted_large(k, cfg)) continue;
        for (int idx : k.segment.indices) {
          const float cv = c.curvature[std::size_t(idx)];
          if (!std::isfinite(cv)) continue;
          (c.labels[std::size_t(idx)] ? head : other).push_back(cv);
        }
      }
    }
  }
  auto q = [](std::vector<float> v, double p) {
    if (v.empty()) return double(NAN);
    std::nth_element(v.begin(), v.begin() + long(p * double(v.size() - 1)), v.end());
    return double(v[std::size_t(p * double(v.size() - 1))]);
  };
  std::printf("head px %zu: q10 %.4f q25 %.4f q50 %.4f q75 %.4f\n", head.size(), q(head, 0.1), q(head, 0.25),
              q(head, 0.5), q(head, 0.75));
  std::printf("other px %zu: q10 %.4f q25 %.4f q50 %.4f q75 %.4f q90 %.4f\n", other.size(), q(other, 0.1),
              q(other, 0.25), q(other, 0.5), q(other, 0.75), q(other, 0.9));
  // AUC from the ranks (Mann-Whitney U).
  std::vector<std::pair<float, int>> all;
  for (float v : head) all.push_back({v, 1});
  for (float v : other) all.push_back({v, 0});
  std::sort(all.begin(), all.end());
  double rank_sum = 0;
  for (std::size_t r = 0; r < all.size(); ++r)
    if (all[r].second) rank_sum += double(r + 1);
  const double nh = double(head.size()), no = double(other.size());
  std::printf("AUC (head curvature > other) %.3f\n", (rank_sum - nh * (nh + 1) / 2) / (nh * no));
  return 0;
}
