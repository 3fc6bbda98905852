// The broccoli report: precision–recall curves against eval::DetectionApAccumulator, the charts,
// and the page rendered by headless Chromium (skipped with a message when chromium is absent).
// `cropsight report --model` itself is tested in tests/cli/test_tracking_cli.cpp.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <span>

#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/broccoli_report.hpp"
#include "cropsight/report/broccoli_run_data.hpp"
#include "cropsight/report/sequence_page.hpp"
#include "cropsight/report/sequence_summary.hpp"
#include "cropsight/report/svg_charts.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::report;

namespace {

std::vector<PrFrame> random_frames(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> start(0, 900), len(5, 60), count(0, 4);
  std::uniform_real_distribution<float> score(-1.0f, 1.0f);
  std::vector<PrFrame> frames(12);
  for (auto& f : frames) {
    const int n_truth = count(rng);
    for (int t = 0; t < n_truth; ++t) {
      std::vector<int> s;
      const int a = 1000 * t + start(rng) / 10, n = len(rng);
      for (int i = 0; i < n; ++i) s.push_back(a + i);
      f.truth.push_back(s);
      // a detection overlapping it by a random shift, sometimes two (a duplicate)
      for (int k = 0; k < 1 + (t % 2); ++k) {
        const int shift = std::uniform_int_distribution<int>(0, n)(rng);
        std::vector<int> d;
        for (int i = 0; i < n; ++i) d.push_back(a + shift + i);
        f.detections.push_back({score(rng), d});
      }
    }
    for (int k = 0; k < count(rng); ++k) {  // false positives
      std::vector<int> d;
      const int a = 50000 + start(rng);
      for (int i = 0; i < len(rng); ++i) d.push_back(a + i);
      f.detections.push_back({score(rng), d});
    }
  }
  return frames;
}

std::string run(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

const char* kChromium = "/usr/bin/chromium";

std::string chromium(const std::filesystem::path& profile) {
  return std::string(kChromium) +
         " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
         "--disable-component-update --disable-sync --user-data-dir=" +
         profile.string() + " ";
}

int count_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

BroccoliReportData sample_data() {
  BroccoliReportData d;
  d.sequence = "uk-test";
  d.model = "models/broccoli-uk-oes.json";
  d.estimator = "bbox";
  d.frames = 10;
  d.metrics = {{"map_precision", "0.960"}, {"map_recall", "0.920"}};
  const auto frames = random_frames(3);
  d.pr_single = pr_curves(frames, coco_thresholds());
  d.pr_tracked = pr_curves(frames, coco_thresholds());
  for (int i = 0; i < 8; ++i) {
    d.true_heads.push_back({0.38 * i, (i % 2) * 0.6, 100.0 + 8 * i, i != 3});
    if (i != 3) d.map_heads.push_back({0.38 * i + 0.01, (i % 2) * 0.6 - 0.01, 104.0 + 8 * i, true});
    d.head_sizes.push_back({100.0 + 8 * i, 104.0 + 8 * i});
    d.frame_errors.push_back({0.05 * i, 3.0 - i, -20.0 + i});
    d.camera_path.emplace_back(0.3 * i, 0.3);
  }
  d.map_heads.push_back({1.1, 0.2, 90, false});
  d.stages = {{"cloud", 5.0, 10}, {"normals", 12.0, 10}, {"clustering", 8.0, 10}};
  d.tracking_ms = 0.2;
  ColorImage img(64, 48, Rgb8{30, 120, 60});
  d.overlays.push_back(make_figure(img, "frame 0"));
  return d;
}

}  // namespace

TEST(BroccoliReport, PrCurvesAgreeWithTheApAccumulator) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const auto frames = random_frames(seed);
    eval::DetectionApAccumulator acc;
    for (const auto& f : frames) {
      std::vector<eval::DetectionApAccumulator::Scored> s;
      for (const auto& d : f.detections) s.push_back({d.score, std::span<const int>(d.indices)});
      acc.add_frame(f.truth, s);
    }
    const auto curves = pr_curves(frames, coco_thresholds());
    ASSERT_EQ(curves.size(), 10u);
    for (const auto& c : curves) {
      EXPECT_NEAR(c.ap, acc.ap(c.iou), 1e-12) << "seed " << seed << " IoU " << c.iou;
      ASSERT_EQ(c.recall.size(), std::size_t(acc.num_detections()));
      for (std::size_t i = 1; i < c.recall.size(); ++i) EXPECT_GE(c.recall[i], c.recall[i - 1]);
    }
    EXPECT_GE(curves.front().ap, curves.back().ap);  // stricter IoU never helps
  }
}

TEST(BroccoliReport, ChartsDrawEveryMark) {
  ScatterSeries a{"a", {0, 1, 2, NAN}, {0, 1, 4, 1}, {}, "#123", false};
  ScatterSeries b{"b", {0.5}, {0.5}, {0.1}, "#456", true};
  ScatterOptions o;
  o.diagonal = true;
  o.equal_aspect = true;
  const std::string svg = svg_scatter_plot({a, b}, o);
  EXPECT_EQ(count_of(svg, "class=\"cs-mark\""), 4);  // the NaN point is skipped
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  const std::string bars = svg_bar_chart({{"cloud", 1.5}, {"normals <&>", 3.0}}, "t", "ms");
  EXPECT_EQ(count_of(bars, "class=\"cs-mark\""), 2);
  EXPECT_NE(bars.find("normals &lt;&amp;&gt;"), std::string::npos);
}

// `cropsight report --model` adds the sequence sections first and the broccoli sections after
// (apps/cropsight/cmd_report.cpp); the page must still open with the result — detections over
// frames, field map, sizes, timing, then the figures against truth — and only then the data summary.
TEST(BroccoliReport, PageOpensWithTheResultThenTheData) {
  cropsight::testing::TempDir dir;
  cropsight::testing::write_fixture_sequence(dir / "seq", 5);
  const io::SequenceReader reader(dir / "seq");
  HtmlPage page("demo order");
  add_sequence_sections(page, reader, summarize_sequence(reader), {});
  add_broccoli_sections(page, sample_data());
  const std::string html = page.html();
  const std::vector<std::string> order = {"<h2>Broccoli heads: detections over frames</h2>",
                                          "<h2>Field map</h2>",
                                          "<h2>Size</h2>",
                                          "<h2>Timing</h2>",
                                          "<h2>Key figures</h2>",
                                          "<h2>Precision–recall",
                                          "<h2>Sequence summary</h2>",
                                          "<h2>Camera</h2>",
                                          "<h2>Frames</h2>",
                                          "<h2>Ground truth</h2>"};
  std::size_t prev = 0;
  for (const auto& h : order) {
    const std::size_t p = html.find(h);
    ASSERT_NE(p, std::string::npos) << h;
    EXPECT_GT(p, prev) << h << " is out of order";
    prev = p;
  }
  // The first heading after the title is the result, and the detections' frames (embedded PNGs)
  // come before the metadata table.
  EXPECT_EQ(html.find("<h2>"), html.find(order.front()));
  EXPECT_LT(html.find("data:image/png;base64,"), html.find("<h2>Sequence summary</h2>"));
  EXPECT_LT(html.find("<h2>Timing</h2>"), html.find("ground-truth instances"));
}

TEST(BroccoliReport, PageRendersInHeadlessChromium) {
  HtmlPage page("broccoli report test");
  add_broccoli_sections(page, sample_data());
  const std::string html = page.html();
  EXPECT_EQ(count_of(html, "<svg"), 6);                   // PR ×2, field map, size, error vs distance, timing
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);  // self-contained: nothing fetched
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  cropsight::testing::TempDir dir;
  page.write(dir / "report.html");
  if (!std::filesystem::exists(kChromium)) GTEST_SKIP() << "chromium not installed at " << kChromium;
  const std::string dom =
      run(chromium(dir / "profile-dom") + "--dump-dom file://" + (dir / "report.html").string() + " 2>/dev/null");
  ASSERT_FALSE(dom.empty()) << "chromium produced no DOM";
  EXPECT_EQ(count_of(dom, "<svg"), count_of(html, "<svg"));
  EXPECT_GE(count_of(dom, "cs-mark"), 20);
  EXPECT_NE(dom.find("Field map"), std::string::npos);
  EXPECT_NE(dom.find("Precision"), std::string::npos);
  EXPECT_LT(dom.find("detections over frames"), dom.find("Field map"));  // the browser keeps the order
  EXPECT_LT(dom.find("Timing"), dom.find("Precision"));

  // A screenshot: the plots must paint something other than the white page.
  run(chromium(dir / "profile-shot") + "--window-size=1000,3000 --screenshot=" + (dir / "shot.png").string() +
      " file://" + (dir / "report.html").string() + " 2>/dev/null");
  ASSERT_TRUE(std::filesystem::exists(dir / "shot.png")) << "chromium wrote no screenshot";
  const ColorImage shot = io::read_color(dir / "shot.png");
  long coloured = 0;
  for (const auto& p : shot.data)
    if (std::abs(int(p.r) - int(p.g)) > 40 || std::abs(int(p.g) - int(p.b)) > 40) ++coloured;
  EXPECT_GT(coloured, 2000) << "the screenshot shows almost no coloured plot marks";
}

// A pass without ground truth (a user's recording): the recorder keeps the chosen frames, colours
// a detection by whether its head reached the map, counts what was found; the page shows no
// metric section and renders in Chromium.
TEST(BroccoliReport, APassWithoutGroundTruthShowsWhatWasFound) {
  BroccoliRunRecorder recorder({1});
  for (int f = 0; f < 3; ++f) {
    RgbdFrame frame;
    frame.depth = DepthImage(64, 48, std::uint16_t(800));
    frame.camera.depth_scale = 0.001;
    pipeline::broccoli::FrameResult r;
    Detection kept, dropped;
    kept.indices = {64 * 10 + 10, 64 * 10 + 11};
    kept.track_id = 1;
    dropped.indices = {64 * 30 + 40};
    dropped.track_id = 2;
    r.detections = {kept, dropped};
    r.association.camera_position = Eigen::Vector3d(0.1 * f, 0.0, 0.0);
    recorder.add_frame(frame, r);
  }
  tracking::TrackedHead head;
  head.id = 1;
  head.position = Eigen::Vector3d(0.2, 0.3, 0.0);
  head.diameter_mm = 120.0;
  head.harvestable = true;
  const BroccoliReportData d = recorder.finish({head}, {{"normals", 3.0, 3}}, "own", "general", "hull");
  EXPECT_FALSE(d.has_truth);
  EXPECT_EQ(d.frames, 3);
  EXPECT_EQ(d.detections_per_frame, (std::vector<int>{2, 2, 2}));
  ASSERT_EQ(d.overlays.size(), 1u);  // frame 1 only
  ASSERT_EQ(d.map_heads.size(), 1u);
  EXPECT_EQ(d.map_heads[0].diameter_mm, 120.0);
  const auto metric = [&](const std::string& k) {
    for (const auto& [key, value] : d.metrics)
      if (key == k) return value;
    return std::string("missing");
  };
  EXPECT_EQ(metric("detections"), "6");
  EXPECT_EQ(metric("map_heads"), "1");
  EXPECT_EQ(metric("harvestable_heads"), "1");
  EXPECT_EQ(metric("median_diameter_mm"), "120.0");

  HtmlPage page("own recording");
  add_broccoli_sections(page, d);
  const std::string html = page.html();
  EXPECT_EQ(html.find("Precision–recall"), std::string::npos);
  EXPECT_EQ(html.find("true heads"), std::string::npos);
  EXPECT_EQ(count_of(html, "<svg"), 4);  // detections per frame, field map, size distribution, timing
  cropsight::testing::TempDir dir;
  page.write(dir / "own.html");
  if (!std::filesystem::exists(kChromium)) GTEST_SKIP() << "chromium not installed at " << kChromium;
  const std::string dom =
      run(chromium(dir / "profile-dom") + "--dump-dom file://" + (dir / "own.html").string() + " 2>/dev/null");
  ASSERT_FALSE(dom.empty()) << "chromium produced no DOM";
  EXPECT_EQ(count_of(dom, "<svg"), 4);
  for (const char* section : {"detections over frames", "Field map", "Size", "Timing", "Key figures"})
    EXPECT_NE(dom.find(section), std::string::npos) << section;
}
