// A tuning tool (not a test): an upper bound for segmenting heads from depth tops. For each visible
// head (>= 300 points) that no cluster of the detector covers with IoU >= 0.5, it asks whether a
// region grown from a local depth top of the detector's unaccepted clusters (rejected ones of
// detection.split_min_points or more, oversized regions) would: from every pixel that is the nearest in its 15×15
// window, a breadth-first growth over 4-neighbours within oes.distance_tolerance keeps the pixels
// within R of the seed across the view (x, y) and no deeper than a sphere of radius R through the
// seed (+ 1 cm), for R in {35, 50, 65, 80} mm. The best IoU over seeds and radii is an oracle's
// choice (no classifier picks among them), so the count is an upper bound. Run as
//
//   build/bin/broccoli_dome_seed_probe MODEL.json seq1[,seq2] [key=value ...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "broccoli_probe_args.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"

using namespace cropsight;
using namespace cropsight::pipeline;
using namespace cropsight::pipeline::broccoli;

namespace {
double iou(const std::vector<int>& a_sorted, const std::vector<char>& in_b, long b_size) {
  long inter = 0;
  for (int i : a_sorted) inter += in_b[std::size_t(i)];
  return double(inter) / double(long(a_sorted.size()) + b_size - inter);
}
}  // namespace

// Long on purpose: a tuning probe read top to bottom: options, the sweep, the table it prints.
int main(int argc, char** argv) {
  const auto args = tools::parse_probe_args("broccoli_dome_seed_probe", argc, argv);
  if (!args) return 2;
  const pipeline::broccoli::DetectorConfig& cfg = args->config;
  pipeline::broccoli::Detector det(cfg);
  det.set_model(args->model);
  const float tol2 = cfg.oes.distance_tolerance * cfg.oes.distance_tolerance;
  const double radii[] = {0.035, 0.05, 0.065, 0.08};
  long missed = 0, recoverable = 0, seeds_total = 0, frames = 0;
  std::vector<TruthInstance> truth;
  for (const std::string& dir : args->sequences) {
    io::SequenceReader reader(dir);
    for (int f = 0; f < reader.size(); ++f, ++frames) {
      const auto cands = det.process(reader.read(f));
      const OrganizedCloud& c = det.cloud();
      const int w = c.width, h = c.height;
      truth_instances(c, 300, truth);
      // Region of each pixel among the unaccepted clusters (-1: none).
      std::vector<int> region(c.size(), -1);
      for (std::size_t k = 0; k < cands.size(); ++k)
        if (tools::unaccepted_large(cands[k], cfg))
          for (int i : cands[k].segment.indices) region[std::size_t(i)] = int(k);
      // Missed heads: no candidate with IoU >= 0.5.
      std::vector<const TruthInstance*> miss;
      for (const auto& t : truth) {
        std::vector<char> in(c.size(), 0);
        for (int i : t.indices) in[std::size_t(i)] = 1;
        double best = 0.0;
        for (const auto& k : cands) best = std::max(best, iou(k.segment.indices, in, long(t.indices.size())));
        if (best < 0.5) miss.push_back(&t);
      }
      if (miss.empty()) continue;
      missed += long(miss.size());
      std::vector<double> best(miss.size(), 0.0);
      std::vector<std::vector<char>> masks(miss.size(), std::vector<char>(c.size(), 0));
      for (std::size_t m = 0; m < miss.size(); ++m)
        for (int i : miss[m]->indices) masks[m][std::size_t(i)] = 1;
      std::vector<int> mark(c.size(), -1), queue;
      int stamp = 0;
      for (int v = 7; v < h - 7; ++v)
        for (int u = 7; u < w - 7; ++u) {
          const int s = v * w + u;
          if (region[std::size_t(s)] < 0) continue;
          const float zs = c.z[std::size_t(s)];
          bool top = true;
          for (int dv = -7; dv <= 7 && top; ++dv)
            for (int du = -7; du <= 7 && top; ++du) {
              const int q = s + dv * w + du;
              if (q != s && region[std::size_t(q)] == region[std::size_t(s)] && c.z[std::size_t(q)] < zs) top = false;
            }
          if (!top) continue;
          ++seeds_total;
          for (double R : radii) {
            ++stamp;
            queue.assign(1, s);
            mark[std::size_t(s)] = stamp;
            for (std::size_t qi = 0; qi < queue.size(); ++qi) {
              const int p = queue[qi], pu = p % w;
              for (int q : {pu > 0 ? p - 1 : -1, pu + 1 < w ? p + 1 : -1, p >= w ? p - w : -1,
                            p + w < int(c.size()) ? p + w : -1}) {
                if (q < 0 || mark[std::size_t(q)] == stamp || region[std::size_t(q)] != region[std::size_t(s)])
                  continue;
                const float dx = c.x[std::size_t(p)] - c.x[std::size_t(q)],
                            dy = c.y[std::size_t(p)] - c.y[std::size_t(q)],
                            dz = c.z[std::size_t(p)] - c.z[std::size_t(q)];
                if (dx * dx + dy * dy + dz * dz > tol2) continue;
                const double ex = c.x[std::size_t(q)] - c.x[std::size_t(s)],
                             ey = c.y[std::size_t(q)] - c.y[std::size_t(s)];
                const double d2 = ex * ex + ey * ey;
                if (d2 > R * R) continue;
                if (c.z[std::size_t(q)] - zs > R - std::sqrt(std::max(R * R - d2, 0.0)) + 0.01) continue;
                mark[std::size_t(q)] = stamp;
                queue.push_back(q);
              }
            }
            std::sort(queue.begin(), queue.end());
            for (std::size_t m = 0; m < miss.size(); ++m)
              best[m] = std::max(best[m], iou(queue, masks[m], long(miss[m]->indices.size())));
          }
        }
      for (double b : best) recoverable += b >= 0.5;
    }
  }
  std::printf(
      "frames %ld, visible heads missed by the clusters %ld, reachable from a depth top (IoU >= 0.5, oracle "
      "seed and radius) %ld, seeds %ld (%.1f per frame)\n",
      frames, missed, recoverable, seeds_total, double(seeds_total) / double(std::max(frames, 1L)));
  return 0;
}
