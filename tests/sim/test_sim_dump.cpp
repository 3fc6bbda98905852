// Not a test: renders a few frames to PNG for eyeballing and for docs/img/ (run with
//   CROPSIGHT_SIM_DUMP=DIR test_sim --gtest_also_run_disabled_tests --gtest_filter='*Dump*').
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "cropsight/io/config_yaml.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"
#include "testing/testing.hpp"

namespace {

cv::Mat depth_view(const cropsight::RgbdFrame& f, double zmin, double zmax) {
  cv::Mat gray(f.depth.height, f.depth.width, CV_8UC1);
  for (int v = 0; v < f.depth.height; ++v)
    for (int u = 0; u < f.depth.width; ++u) {
      const double z = f.depth.at(u, v) * f.camera.depth_scale;
      gray.at<std::uint8_t>(v, u) =
          z <= 0 ? 0 : std::uint8_t(std::clamp(255.0 * (zmax - z) / (zmax - zmin), 1.0, 255.0));
    }
  cv::Mat out;
  cv::applyColorMap(gray, out, cv::COLORMAP_TURBO);
  for (int v = 0; v < f.depth.height; ++v)
    for (int u = 0; u < f.depth.width; ++u)
      if (f.depth.at(u, v) == 0) out.at<cv::Vec3b>(v, u) = {0, 0, 0};
  return out;
}

cv::Mat color_view(const cropsight::RgbdFrame& f, bool outline) {
  cv::Mat out(f.color.height, f.color.width, CV_8UC3);
  for (int v = 0; v < f.color.height; ++v)
    for (int u = 0; u < f.color.width; ++u) {
      const auto c = f.color.at(u, v);
      out.at<cv::Vec3b>(v, u) = {c.b, c.g, c.r};
      if (outline && f.labels.at(u, v)) {
        const auto l = f.labels.at(u, v);
        const bool edge = u == 0 || v == 0 || u + 1 == f.color.width || v + 1 == f.color.height ||
                          f.labels.at(u - 1, v) != l || f.labels.at(u + 1, v) != l || f.labels.at(u, v - 1) != l ||
                          f.labels.at(u, v + 1) != l;
        if (edge) out.at<cv::Vec3b>(v, u) = {0, 255, 255};
      }
    }
  return out;
}

// Docs copy: 3/4 size, 5 bits per channel, so that each PNG stays well under 200 KB.
void write_small(const std::string& path, const cv::Mat& img) {
  cv::Mat small;
  cv::resize(img, small, cv::Size(), 0.75, 0.75, cv::INTER_AREA);
  small.forEach<cv::Vec3b>([](cv::Vec3b& p, const int*) {
    for (int k = 0; k < 3; ++k) p[k] = std::uint8_t((p[k] & 0xF8) | 4);
  });
  cv::imwrite(path, small, {cv::IMWRITE_PNG_COMPRESSION, 9});
}

void dump(const std::string& variety, const std::filesystem::path& dir, int frames) {
  // The shipped preset, as `simulate broccoli --variety` applies it.
  cropsight::sim::BroccoliSimConfig cfg;
  const auto preset = cropsight::testing::source_dir() / "configs" / ("sim-broccoli-" + variety + ".yaml");
  cropsight::apply_config(cfg, cropsight::io::load_config_map(preset), preset.string());
  cropsight::sim::BroccoliSimulator sim(cfg, 1, frames);
  for (int i = 0; i < frames; i += std::max(1, frames / 3)) {
    const auto f = sim.render(i);
    const std::string stem = (dir / (variety + "_" + std::to_string(i))).string();
    cv::imwrite(stem + "_depth.png", depth_view(f, 0.5, 1.4));
    cv::imwrite(stem + "_color.png", color_view(f, false));
    cv::imwrite(stem + "_labels.png", color_view(f, true));
    write_small(stem + "_depth_small.png", depth_view(f, 0.5, 1.4));
    write_small(stem + "_labels_small.png", color_view(f, true));
  }
}

}  // namespace

TEST(SimDump, DISABLED_Dump) {
  const char* dir = std::getenv("CROPSIGHT_SIM_DUMP");
  ASSERT_NE(dir, nullptr) << "set CROPSIGHT_SIM_DUMP";
  std::filesystem::create_directories(dir);
  dump("uk", dir, 9);
  dump("spain", dir, 9);
}
