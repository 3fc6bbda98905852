// Organised-cloud stages of the broccoli pipelines, ours against PCL's implementation of the same
// algorithm, on the same 512×424 organised cloud in the same process:
//   normals      IntegralNormalEstimator         vs pcl::IntegralImageNormalEstimation (COVARIANCE_MATRIX)
//   edges        detect_organized_edges          vs pcl::OrganizedEdgeBase
//   clustering   segment_oes / segment_org (flood fill; no PCL counterpart benchmarked)
//   fec          euclidean_clusters (nanoflann)  vs pcl::EuclideanClusterExtraction (+ pcl KdTree)
//   vfh          compute_vfh over the clusters   vs pcl::VFHEstimation per cluster
//   oes/org      end to end: normals + edges + flood fill + VFH of every cluster
// Input: the synthetic scene of tests/geometry/synthetic_scene.hpp, or a recorded/simulated frame
// when CROPSIGHT_BENCH_SEQ=DIR[:FRAME] names a sequence (depth-range filtered 0.5–1.0 m).
// Single-threaded. Run: build/bin/bench_organized --benchmark_counters_tabular=true
// With CROPSIGHT_BENCH_CHECK=1 it first prints the agreement with PCL on the same input (normal
// angles, edge labels, VFH L1 of the OES clusters), e.g. on a simulated frame:
//   CROPSIGHT_BENCH_SEQ=SEQ:10 CROPSIGHT_BENCH_CHECK=1 bench_organized --benchmark_filter=none
#include <benchmark/benchmark.h>
#include <pcl/features/integral_image_normal.h>
#include <pcl/features/organized_edge_detection.h>
#include <pcl/features/vfh.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

#include "../tests/geometry/synthetic_scene.hpp"
#include "cropsight/core/pcl_conversions.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/features/vfh.hpp"
#include "cropsight/geometry/depth_filter.hpp"
#include "cropsight/geometry/integral_normals.hpp"
#include "cropsight/geometry/organized_edges.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/segmentation/euclidean_clustering.hpp"
#include "cropsight/segmentation/organized_clustering.hpp"

using namespace cropsight;

namespace {

// Crease threshold used for OES (see geometry/organized_edges.hpp); ORG curvature threshold.
constexpr float kCrease = 0.02f;

OrganizedCloud load_input() {
  if (const char* seq = std::getenv("CROPSIGHT_BENCH_SEQ")) {
    std::string s = seq;
    int frame = 0;
    if (auto colon = s.rfind(':'); colon != std::string::npos && colon > 1) {
      frame = std::stoi(s.substr(colon + 1));
      s = s.substr(0, colon);
    }
    io::SequenceReader reader(s);
    OrganizedCloud c = to_organized_cloud(reader.read(frame));
    geometry::filter_depth_range(c, {});
    std::cerr << "bench_organized: frame " << frame << " of " << s << " (" << c.width << "x" << c.height << ", "
              << c.count_valid() << " valid points)\n";
    return c;
  }
  auto scene = cropsight::testing::make_synthetic_scene();
  std::cerr << "bench_organized: synthetic scene 512x424, " << scene.cloud.count_valid() << " valid points\n";
  return scene.cloud;
}

const OrganizedCloud& input() {
  static const OrganizedCloud c = load_input();
  return c;
}

const OrganizedCloud& input_with_normals() {
  static const OrganizedCloud c = [] {
    OrganizedCloud x = input();
    geometry::estimate_normals_integral(x);
    return x;
  }();
  return c;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr pcl_input() {
  static auto pc = [] {
    auto p = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    to_pcl(input(), *p);
    return p;
  }();
  return pc;
}

std::vector<Segment> oes_segments(const OrganizedCloud& c) {
  segmentation::OrganizedClusteringWorkspace ws;
  const auto edges = geometry::detect_organized_edges(c, {.high_curvature_threshold = kCrease});
  return segmentation::segment_oes(c, edges, {}, ws);
}

// ---------------------------------------------------------------- normals
void BM_Normals_Ours(benchmark::State& st) {
  OrganizedCloud c = input();
  geometry::IntegralNormalEstimator est;
  for (auto _ : st) {
    est.compute(c);
    benchmark::DoNotOptimize(c.nx.data());
  }
}
BENCHMARK(BM_Normals_Ours)->Unit(benchmark::kMillisecond);

void BM_Normals_PCL(benchmark::State& st) {
  auto pc = pcl_input();
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  ne.setNormalEstimationMethod(ne.COVARIANCE_MATRIX);
  ne.setMaxDepthChangeFactor(0.02f);
  ne.setNormalSmoothingSize(10.0f);
  pcl::PointCloud<pcl::Normal> out;
  for (auto _ : st) {
    ne.setInputCloud(pc);  // PCL rebuilds its integral images on setInputCloud
    ne.compute(out);
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_Normals_PCL)->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- edges
void BM_Edges_Ours(benchmark::State& st) {
  const OrganizedCloud& c = input();
  std::vector<std::uint8_t> labels;
  for (auto _ : st) {
    geometry::detect_organized_edges(c, {}, labels);
    benchmark::DoNotOptimize(labels.data());
  }
}
BENCHMARK(BM_Edges_Ours)->Unit(benchmark::kMillisecond);

void BM_Edges_PCL(benchmark::State& st) {
  auto pc = pcl_input();
  pcl::OrganizedEdgeBase<pcl::PointXYZ, pcl::Label> oed;
  oed.setInputCloud(pc);
  oed.setDepthDisconThreshold(0.02f);
  oed.setMaxSearchNeighbors(50);
  pcl::PointCloud<pcl::Label> labels;
  std::vector<pcl::PointIndices> idx;
  for (auto _ : st) {
    oed.compute(labels, idx);
    benchmark::DoNotOptimize(labels.data());
  }
}
BENCHMARK(BM_Edges_PCL)->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- flood fill
void BM_FloodFill_OES(benchmark::State& st) {
  const OrganizedCloud& c = input_with_normals();
  const auto edges = geometry::detect_organized_edges(c, {.high_curvature_threshold = kCrease});
  segmentation::OrganizedClusteringWorkspace ws;
  std::size_t n = 0;
  for (auto _ : st) {
    auto segs = segmentation::segment_oes(c, edges, {}, ws);
    n = segs.size();
    benchmark::DoNotOptimize(segs.data());
  }
  st.counters["segments"] = double(n);
}
BENCHMARK(BM_FloodFill_OES)->Unit(benchmark::kMillisecond);

void BM_FloodFill_ORG(benchmark::State& st) {
  const OrganizedCloud& c = input_with_normals();
  segmentation::OrganizedClusteringWorkspace ws;
  std::size_t n = 0;
  for (auto _ : st) {
    auto segs = segmentation::segment_org(c, {.curvature_threshold = kCrease}, ws);
    n = segs.size();
    benchmark::DoNotOptimize(segs.data());
  }
  st.counters["segments"] = double(n);
}
BENCHMARK(BM_FloodFill_ORG)->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- Euclidean clustering
void BM_Fec_Ours(benchmark::State& st) {
  const OrganizedCloud& c = input();
  const auto idx = geometry::valid_indices(c);
  std::size_t n = 0;
  for (auto _ : st) {
    auto segs = segmentation::euclidean_clusters(c, idx, {});
    n = segs.size();
    benchmark::DoNotOptimize(segs.data());
  }
  st.counters["clusters"] = double(n);
}
BENCHMARK(BM_Fec_Ours)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_Fec_PCL(benchmark::State& st) {
  const OrganizedCloud& c = input();
  auto pc = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (int i : geometry::valid_indices(c)) pc->push_back(pcl::PointXYZ(c.x[i], c.y[i], c.z[i]));
  std::size_t n = 0;
  for (auto _ : st) {
    auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(0.005);
    ec.setMinClusterSize(500);
    ec.setMaxClusterSize(10000);
    ec.setSearchMethod(tree);
    ec.setInputCloud(pc);
    std::vector<pcl::PointIndices> out;
    ec.extract(out);
    n = out.size();
    benchmark::DoNotOptimize(out.data());
  }
  st.counters["clusters"] = double(n);
}
BENCHMARK(BM_Fec_PCL)->Unit(benchmark::kMillisecond)->Iterations(3);

// ---------------------------------------------------------------- VFH of the OES clusters
void BM_Vfh_Ours(benchmark::State& st) {
  const OrganizedCloud& c = input_with_normals();
  const auto segs = oes_segments(c);
  std::vector<float> h(features::kVfhBins);
  std::size_t points = 0;
  for (const auto& s : segs) points += s.size();
  for (auto _ : st)
    for (const auto& s : segs) {
      features::compute_vfh(c, s.indices, {}, h.data());
      benchmark::DoNotOptimize(h.data());
    }
  st.counters["clusters"] = double(segs.size());
  st.counters["points"] = double(points);
}
BENCHMARK(BM_Vfh_Ours)->Unit(benchmark::kMillisecond);

void BM_Vfh_PCL(benchmark::State& st) {
  const OrganizedCloud& c = input_with_normals();
  const auto segs = oes_segments(c);
  pcl::PointCloud<pcl::VFHSignature308> out;
  for (auto _ : st)
    for (const auto& s : segs) {
      // The PCL user's way: the cluster's points and normals copied into their own clouds (so
      // that the k-d tree VFHEstimation insists on building covers the cluster only), the same
      // points compute_vfh uses (finite normals).
      auto pts = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
      auto nrm = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
      for (int i : s.indices)
        if (std::isfinite(c.nx[i])) {
          pts->push_back(pcl::PointXYZ(c.x[i], c.y[i], c.z[i]));
          nrm->push_back(pcl::Normal(c.nx[i], c.ny[i], c.nz[i], c.curvature[i]));
        }
      pcl::VFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> vfh;
      vfh.setInputCloud(pts);
      vfh.setInputNormals(nrm);
      vfh.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
      vfh.compute(out);
      benchmark::DoNotOptimize(out.data());
    }
  st.counters["clusters"] = double(segs.size());
}
BENCHMARK(BM_Vfh_PCL)->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- end to end (our stages)
template <bool kOes>
void BM_EndToEnd(benchmark::State& st) {
  OrganizedCloud c = input();
  geometry::IntegralNormalEstimator est;
  segmentation::OrganizedClusteringWorkspace ws;
  std::vector<std::uint8_t> edges;
  std::vector<float> h(features::kVfhBins);
  std::size_t n = 0;
  for (auto _ : st) {
    est.compute(c);
    std::vector<Segment> segs;
    if constexpr (kOes) {
      geometry::detect_organized_edges(c, {.high_curvature_threshold = kCrease}, edges);
      segs = segmentation::segment_oes(c, edges, {}, ws);
    } else {
      segs = segmentation::segment_org(c, {.curvature_threshold = kCrease}, ws);
    }
    for (const auto& s : segs) {
      features::compute_vfh(c, s.indices, {}, h.data());
      benchmark::DoNotOptimize(h.data());
    }
    n = segs.size();
  }
  st.counters["segments"] = double(n);
  st.counters["fps"] = benchmark::Counter(double(st.iterations()), benchmark::Counter::kIsRate);
}
void BM_EndToEnd_OES(benchmark::State& st) { BM_EndToEnd<true>(st); }
void BM_EndToEnd_ORG(benchmark::State& st) { BM_EndToEnd<false>(st); }
BENCHMARK(BM_EndToEnd_OES)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EndToEnd_ORG)->Unit(benchmark::kMillisecond);

// Agreement with PCL on the benchmark input (the unit tests assert it on the synthetic scene).
void print_agreement() {
  const OrganizedCloud& c = input();
  const OrganizedCloud& ours = input_with_normals();
  auto pc = pcl_input();
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  ne.setNormalEstimationMethod(ne.COVARIANCE_MATRIX);
  ne.setMaxDepthChangeFactor(0.02f);
  ne.setNormalSmoothingSize(10.0f);
  ne.setInputCloud(pc);
  pcl::PointCloud<pcl::Normal> ref;
  ne.compute(ref);
  std::vector<double> ang;
  std::size_t only_ours = 0, only_pcl = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const bool a = std::isfinite(ours.nx[i]), b = std::isfinite(ref[i].normal_x);
    if (a && b) {
      const double d = double(ours.nx[i]) * ref[i].normal_x + double(ours.ny[i]) * ref[i].normal_y +
                       double(ours.nz[i]) * ref[i].normal_z;
      ang.push_back(std::acos(std::clamp(d, -1.0, 1.0)) * 180.0 / M_PI);
    } else {
      only_ours += a, only_pcl += b;
    }
  }
  std::sort(ang.begin(), ang.end());
  std::cerr << "check normals: valid in both " << ang.size() << ", only ours " << only_ours << ", only PCL "
            << only_pcl;
  if (!ang.empty())
    std::cerr << "; angle median " << ang[ang.size() / 2] << " deg, p95 " << ang[ang.size() * 95 / 100] << " deg";
  std::cerr << "\n";

  const auto el = geometry::detect_organized_edges(c);
  pcl::OrganizedEdgeBase<pcl::PointXYZ, pcl::Label> oed;
  oed.setInputCloud(pc);
  oed.setDepthDisconThreshold(0.02f);
  oed.setMaxSearchNeighbors(50);
  pcl::PointCloud<pcl::Label> lab;
  std::vector<pcl::PointIndices> li;
  oed.compute(lab, li);
  std::size_t agree = 0, edges = 0;
  for (std::size_t i = 0; i < c.size(); ++i) agree += el[i] == lab[i].label, edges += lab[i].label != 0;
  std::cerr << "check edges: label agreement " << 100.0 * double(agree) / double(c.size()) << " % (" << edges
            << " PCL edge pixels)\n";

  double worst = 0, sum = 0;
  const auto segs = oes_segments(ours);
  for (const auto& s : segs) {
    auto pts = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    auto nrm = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
    std::vector<int> idx;
    for (int i : s.indices)
      if (std::isfinite(ours.nx[i])) {
        idx.push_back(i);
        pts->push_back(pcl::PointXYZ(ours.x[i], ours.y[i], ours.z[i]));
        nrm->push_back(pcl::Normal(ours.nx[i], ours.ny[i], ours.nz[i], ours.curvature[i]));
      }
    if (idx.size() < 2) continue;
    pcl::VFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> vfh;
    vfh.setInputCloud(pts);
    vfh.setInputNormals(nrm);
    vfh.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
    pcl::PointCloud<pcl::VFHSignature308> out;
    vfh.compute(out);
    const auto h = features::compute_vfh(ours, idx);
    double l1 = 0;
    for (int b = 0; b < features::kVfhBins; ++b) l1 += std::abs(double(h[b]) - out[0].histogram[b]);
    worst = std::max(worst, l1);
    sum += l1;
  }
  std::cerr << "check VFH: " << segs.size() << " OES clusters, L1 to PCL mean "
            << (segs.empty() ? 0.0 : sum / double(segs.size())) << ", max " << worst
            << " (each histogram sums to ~400)\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (const char* check = std::getenv("CROPSIGHT_BENCH_CHECK"); check && std::string(check) == "1") print_agreement();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
