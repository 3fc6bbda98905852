// Tracking + sizing cost per frame (target: under 0.5 ms per frame added to the pipeline).
//
// Synthetic frames shaped like the simulated UK sequences: a 512×424 pinhole camera (Kinect v2
// field of view) 0.75 m above the heads moving 4 cm per frame (0.3 m/s at 7.5 fps) over two rows,
// so about 4–5 heads are in view, each a dome of 60–180 mm ray-cast per pixel with 1 mm depth
// noise along the ray and millimetre depth quantisation (about 2 mm pixel pitch on the heads,
// 700–6000 points per head). Each head is stored as a crop of the organised cloud around it, as
// the pipeline hands the sizer pixel indices into the frame. Each benchmark iteration processes
// one frame:
//   BM_Size/H/N/P/E    sizing of every head in the frame: H = 0 bounding box only, 1 + convex
//                      hull; N > 0: hull of an even subsample of at most N points; P = 1: hull
//                      of the row/column hull candidates (hull_prefilter); E = 1 qhull via PCL
//                      (the paper's library), 0 our Quickhull. /1/0/0/1 is the paper's setup,
//                      /1/0/1/0 the default config.
//   BM_Track           the temporal filter alone (detections already sized)
//   BM_TrackAndSize/H/P/E  what the pipeline adds per frame: sizing from the organised cloud
//                      (copying the head's points) and tracking, same H, P, E; /1/1/0 is the
//                      default config, /1/0/1 the paper's hull
// Ratios to BM_Size/0/0/0/0 (the cheapest stage) are the numbers to compare across machines.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/measure/head_size.hpp"
#include "cropsight/tracking/temporal_filter.hpp"
#include "measure/hull_candidates.hpp"
#include "measure/quickhull.hpp"

using namespace cropsight;

namespace {

struct Head {
  Eigen::Vector3d p;  // field frame (z up), top of the head
  double r;           // m
};

struct HeadView {
  OrganizedCloud crop;               // the frame's organised cloud cropped to the head's pixels
  std::vector<int> indices;          // the head's pixels in `crop`
  std::vector<Eigen::Vector3f> pts;  // their points (camera frame)
};

struct Frames {
  std::vector<std::vector<HeadView>> heads;  // frame → heads in view
  std::vector<std::vector<Eigen::Vector3f>> centroids;
};

Frames make_frames(int n_frames) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> dia(0.06, 0.18), jit(-0.03, 0.03);
  std::normal_distribution<double> noise(0.0, 0.001);
  std::vector<Head> heads;
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < 40; ++k)
      heads.push_back({{0.38 * k + jit(rng), (row ? 0.3 : -0.3) + jit(rng), 0.5}, dia(rng) / 2});
  const CameraIntrinsics cam = CameraIntrinsics::from_fov(512, 424, 70.6 * M_PI / 180, 60.0 * M_PI / 180);
  Frames f;
  for (int i = 0; i < n_frames; ++i) {
    const Eigen::Vector3d cam_pos(0.04 * i, 0.0, 1.25);
    f.heads.emplace_back();
    f.centroids.emplace_back();
    for (const auto& h : heads) {
      // camera frame (default "y,x,-z": camera x = field y, camera y = field x); the sphere's
      // centre lies r below the head's top
      const Eigen::Vector3d rel = h.p - cam_pos;
      const Eigen::Vector3d centre(rel.y(), rel.x(), -rel.z() + h.r);
      const auto uv = cam.project(centre.cast<float>());
      const double rad_px = cam.fx * h.r / (centre.z() - h.r) + 2;
      const int u0 = std::max(0, int(uv.x() - rad_px)), u1 = std::min(cam.width - 1, int(uv.x() + rad_px));
      const int v0 = std::max(0, int(uv.y() - rad_px)), v1 = std::min(cam.height - 1, int(uv.y() + rad_px));
      if (u1 - u0 < 8 || v1 - v0 < 8) continue;
      HeadView view{OrganizedCloud(u1 - u0 + 1, v1 - v0 + 1), {}, {}};
      Eigen::Vector3f c = Eigen::Vector3f::Zero();
      for (int v = v0; v <= v1; ++v)
        for (int u = u0; u <= u1; ++u) {
          const Eigen::Vector3d d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
          const double a = d.squaredNorm(), b = -2 * d.dot(centre), q = centre.squaredNorm() - h.r * h.r;
          const double disc = b * b - 4 * a * q;
          if (disc < 0) continue;
          const double t = (-b - std::sqrt(disc)) / (2 * a);
          if (t > centre.z()) continue;  // below the equator
          const float z = float(0.001 * std::round(1000.0 * (t + noise(rng))));
          const Eigen::Vector3f p = cam.deproject(float(u), float(v), z);
          const int k = view.crop.index(u - u0, v - v0);
          view.crop.x[std::size_t(k)] = p.x();
          view.crop.y[std::size_t(k)] = p.y();
          view.crop.z[std::size_t(k)] = p.z();
          view.indices.push_back(k);
          view.pts.push_back(p);
          c += p;
        }
      if (view.pts.size() < 300) continue;  // a sliver at the image border: no segment
      f.centroids.back().push_back(c / float(view.pts.size()));
      f.heads.back().push_back(std::move(view));
    }
  }
  return f;
}

const Frames& frames() {
  static const Frames f = make_frames(120);
  return f;
}

void BM_Size(benchmark::State& state) {
  measure::HeadSizeConfig cfg;
  cfg.compute_hull = state.range(0) != 0;
  cfg.hull_max_points = int(state.range(1));
  cfg.hull_prefilter = state.range(2) != 0;
  cfg.hull_engine = state.range(3) ? "qhull" : "quickhull";
  const measure::HeadSizer sizer(cfg);
  const auto& f = frames();
  std::size_t i = 0, heads = 0, points = 0, vertices = 0;
  for (auto _ : state) {
    for (const auto& h : f.heads[i]) {
      // the organised call is the only one that can use the prefilter
      const auto s = cfg.hull_prefilter ? sizer.measure(h.crop, h.indices) : sizer.measure(h.pts);
      benchmark::DoNotOptimize(s);
      ++heads;
      points += h.pts.size();
      vertices += std::size_t(s.hull_vertices);
    }
    i = (i + 1) % f.heads.size();
  }
  const double nh = double(std::max<std::size_t>(heads, 1));
  state.counters["heads_per_frame"] = double(heads) / double(state.iterations());
  state.counters["points_per_head"] = double(points) / nh;
  state.counters["hull_vertices_per_head"] = double(vertices) / nh;
  state.SetLabel(!cfg.compute_hull ? "bbox" : "bbox+" + cfg.hull_engine + (cfg.hull_prefilter ? "(prefilter)" : ""));
}
BENCHMARK(BM_Size)
    ->Args({0, 0, 0, 0})
    ->Args({1, 0, 0, 1})
    ->Args({1, 1000, 0, 1})
    ->Args({1, 500, 0, 1})
    ->Args({1, 250, 0, 1})
    ->Args({1, 0, 1, 1})
    ->Args({1, 0, 0, 0})
    ->Args({1, 0, 1, 0})
    ->Args({1, 500, 0, 0})  // our Quickhull of a 500-point stride subsample (the fast setting; needs its own fit)
    ->Args({1, 250, 0, 0})
    ->Unit(benchmark::kMicrosecond);

// The hull stages alone, per frame: the row/column filter, then Quickhull on its candidates.
void BM_HullStage(benchmark::State& state) {
  const auto& f = frames();
  std::vector<std::vector<std::vector<Eigen::Vector3f>>> cand(f.heads.size());
  for (std::size_t i = 0; i < f.heads.size(); ++i)
    for (const auto& h : f.heads[i]) {
      std::vector<Eigen::Vector3f> c;
      const auto idx = measure::hull_vertex_candidates(h.crop, h.indices);
      if (!idx) state.SkipWithError("the synthetic heads should pass the pinhole check");
      for (int k : idx.value_or(std::vector<int>{})) c.push_back(h.crop.point(std::size_t(k)));
      cand[i].push_back(std::move(c));
    }
  std::size_t i = 0, n = 0, heads = 0;
  measure::QuickHull q;
  for (auto _ : state) {
    for (std::size_t k = 0; k < f.heads[i].size(); ++k) {
      if (state.range(0) == 0) {
        const auto c = measure::hull_vertex_candidates(f.heads[i][k].crop, f.heads[i][k].indices);
        n += c ? c->size() : 0;
      } else {
        measure::quickhull(cand[i][k], q);
        n += cand[i][k].size();
      }
      ++heads;
    }
    i = (i + 1) % f.heads.size();
  }
  state.counters["points_per_head"] = double(n) / double(std::max<std::size_t>(heads, 1));
  state.SetLabel(state.range(0) == 0 ? "row/column filter" : "quickhull of the candidates");
}
BENCHMARK(BM_HullStage)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_Track(benchmark::State& state) {
  const auto& f = frames();
  std::vector<std::vector<tracking::HeadObservation>> obs(f.heads.size());
  for (std::size_t i = 0; i < f.heads.size(); ++i)
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
  cfg.hull_prefilter = state.range(1) != 0;
  cfg.hull_engine = state.range(2) ? "qhull" : "quickhull";
  cfg.hull_max_points = int(state.range(3));
  const measure::HeadSizer sizer(cfg);
  const auto& f = frames();
  auto filter = std::make_unique<tracking::TemporalFilter>(tracking::TemporalFilterConfig{}, sizer);
  std::size_t i = 0;
  std::size_t mapped = 0;
  for (auto _ : state) {
    if (i == f.heads.size()) {
      state.PauseTiming();
      mapped += filter->finish().size();
      filter = std::make_unique<tracking::TemporalFilter>(tracking::TemporalFilterConfig{}, sizer);
      i = 0;
      state.ResumeTiming();
    }
    std::vector<tracking::HeadObservation> obs(f.heads[i].size());
    for (std::size_t k = 0; k < obs.size(); ++k) {
      obs[k].centroid = f.centroids[i][k];
      obs[k].score = 1.0f;
      obs[k].size = sizer.measure(f.heads[i][k].crop, f.heads[i][k].indices);  // as HeadMapper does
    }
    benchmark::DoNotOptimize(filter->update(int(i), obs));
    ++i;
  }
  state.SetLabel(!cfg.compute_hull
                     ? "bbox+track"
                     : "bbox+" + cfg.hull_engine + (cfg.hull_prefilter ? "(prefilter)" : "") +
                           (cfg.hull_max_points ? "(<=" + std::to_string(cfg.hull_max_points) + ")" : "") + "+track");
}
// Args: compute_hull, hull_prefilter, qhull engine, hull_max_points.
BENCHMARK(BM_TrackAndSize)
    ->Args({0, 0, 0, 0})
    ->Args({1, 0, 1, 0})
    ->Args({1, 1, 1, 0})
    ->Args({1, 0, 0, 0})
    ->Args({1, 1, 0, 0})
    ->Args({1, 0, 0, 500})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
