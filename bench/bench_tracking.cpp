// Tracking + sizing cost per frame (issue 4 target: under 0.5 ms per frame added to the pipeline).
//
// Synthetic frames shaped like the simulated UK sequences: a camera 0.75 m above the heads moving
// 4 cm per frame (0.3 m/s at 7.5 fps) over two rows, so about 6 heads are in view, each a noisy
// dome of 60–180 mm seen from above with the pixel pitch of a 512×424 ToF camera at that range
// (about 2 mm), i.e. 700–6000 points per head. Each benchmark iteration processes one frame:
//   BM_Size/bbox      bounding-box sizing of every head in the frame
//   BM_Size/hull      convex-hull sizing of every head (qhull via PCL)
//   BM_Track          the temporal filter alone (detections already sized)
//   BM_TrackAndSize   what the pipeline adds per frame with the default config (bbox + hull +
//                     tracking), and with compute_hull=false (bbox + tracking)
// Ratios to BM_Size/bbox (the cheapest stage) are the numbers to compare across machines.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>

#include "cropsight/measure/head_size.hpp"
#include "cropsight/tracking/temporal_filter.hpp"

using namespace cropsight;

namespace {

struct Head {
  Eigen::Vector3d p;  // field frame (z up), top of the head
  double r;           // m
};

struct Frames {
  std::vector<std::vector<std::vector<Eigen::Vector3f>>> points;  // frame → head → camera-frame points
  std::vector<std::vector<Eigen::Vector3f>> centroids;
};

Frames make_frames(int n_frames) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> dia(0.06, 0.18), jit(-0.03, 0.03);
  std::normal_distribution<float> noise(0.0f, 0.001f);
  std::vector<Head> heads;
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < 40; ++k)
      heads.push_back({{0.38 * k + jit(rng), (row ? 0.3 : -0.3) + jit(rng), 0.5}, dia(rng) / 2});
  Frames f;
  const double step = 0.002;  // pixel pitch on the heads
  for (int i = 0; i < n_frames; ++i) {
    const Eigen::Vector3d cam(0.04 * i, 0.0, 1.25);
    f.points.emplace_back();
    f.centroids.emplace_back();
    for (const auto& h : heads) {
      const Eigen::Vector3d rel = h.p - cam;
      if (std::abs(rel.x()) > 0.42 || std::abs(rel.y()) > 0.5) continue;
      std::vector<Eigen::Vector3f> pts;
      Eigen::Vector3f c = Eigen::Vector3f::Zero();
      const int n = int(h.r / step);
      for (int a = -n; a <= n; ++a)
        for (int b = -n; b <= n; ++b) {
          const double x = a * step, y = b * step, q = h.r * h.r - x * x - y * y;
          if (q < 0) continue;
          // camera frame (default "y,x,-z": camera x = field y, camera y = field x); the dome
          // bulges towards the camera
          const Eigen::Vector3f p(float(rel.y() + y) + noise(rng), float(rel.x() + x) + noise(rng),
                                  float(-rel.z() - std::sqrt(q) + h.r) + noise(rng));
          pts.push_back(p);
          c += p;
        }
      f.centroids.back().push_back(c / float(pts.size()));
      f.points.back().push_back(std::move(pts));
    }
  }
  return f;
}

const Frames& frames() {
  static const Frames f = make_frames(200);
  return f;
}

void BM_Size(benchmark::State& state) {
  measure::HeadSizeConfig cfg;
  cfg.compute_hull = state.range(0) != 0;
  cfg.hull_max_points = int(state.range(1));
  const measure::HeadSizer sizer(cfg);
  const auto& f = frames();
  std::size_t i = 0, heads = 0, points = 0;
  for (auto _ : state) {
    for (const auto& h : f.points[i]) {
      benchmark::DoNotOptimize(sizer.measure(h));
      ++heads;
      points += h.size();
    }
    i = (i + 1) % f.points.size();
  }
  state.counters["heads_per_frame"] = double(heads) / double(state.iterations());
  state.counters["points_per_head"] = double(points) / double(std::max<std::size_t>(heads, 1));
  state.SetLabel(cfg.compute_hull ? "bbox+hull" : "bbox");
}
BENCHMARK(BM_Size)->Args({0, 0})->Args({1, 0})->Args({1, 1000})->Args({1, 500})->Args({1, 250})->Unit(
    benchmark::kMicrosecond);

void BM_Track(benchmark::State& state) {
  const auto& f = frames();
  std::vector<std::vector<tracking::HeadObservation>> obs(f.points.size());
  for (std::size_t i = 0; i < f.points.size(); ++i)
    for (const auto& c : f.centroids[i]) {
      tracking::HeadObservation o;
      o.centroid = c;
      o.score = 1.0f;
      o.size.valid = true;
      o.size.bbox_mm = 120.0;
      obs[i].push_back(o);
    }
  auto filter = std::make_unique<tracking::TemporalFilter>();
  std::size_t i = 0;
  for (auto _ : state) {
    if (i == obs.size()) {  // a new pass: restart outside the timed region
      state.PauseTiming();
      filter->finish();
      filter = std::make_unique<tracking::TemporalFilter>();
      i = 0;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(filter->update(int(i), obs[i]));
    ++i;
  }
}
BENCHMARK(BM_Track)->Unit(benchmark::kMicrosecond);

void BM_TrackAndSize(benchmark::State& state) {
  measure::HeadSizeConfig cfg;
  cfg.compute_hull = state.range(0) != 0;
  const measure::HeadSizer sizer(cfg);
  const auto& f = frames();
  auto filter = std::make_unique<tracking::TemporalFilter>(tracking::TemporalFilterConfig{}, sizer);
  std::size_t i = 0;
  std::size_t mapped = 0;
  for (auto _ : state) {
    if (i == f.points.size()) {
      state.PauseTiming();
      mapped += filter->finish().size();
      filter = std::make_unique<tracking::TemporalFilter>(tracking::TemporalFilterConfig{}, sizer);
      i = 0;
      state.ResumeTiming();
    }
    std::vector<tracking::HeadObservation> obs(f.points[i].size());
    for (std::size_t k = 0; k < obs.size(); ++k) {
      obs[k].centroid = f.centroids[i][k];
      obs[k].score = 1.0f;
      obs[k].size = sizer.measure(f.points[i][k]);
    }
    benchmark::DoNotOptimize(filter->update(int(i), obs));
    ++i;
  }
  state.SetLabel(cfg.compute_hull ? "bbox+hull+track" : "bbox+track");
}
BENCHMARK(BM_TrackAndSize)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
