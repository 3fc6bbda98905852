// Tuning probe: the chroma of potato pixels against the chroma of the image's bright
// background, per image, on the detection set (VOC boxes) and on the orientation shots (boxes of
// BoardBlobDetector). Shows whether the skin colour model holds across the two real scenes, and
// whether a white reference taken from the image explains the difference.
// Usage: potato_probe DETECTION_DIR ORIENTATION_DIR [OVERLAY_DIR]
//        potato_probe --fit IMAGES ANNOTATIONS   (the skin colour fit of one VOC set)
//        potato_probe --lab IMAGE x y [x y ...]  (Lab, chroma and saturation of 5x5 means)
//        potato_probe --orient IMAGE x1 y1 x2 y2 rgb|depth OUT.png  (the orientation mask of one box)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "cropsight/core/statistics.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/measure/orientation.hpp"
#include "cropsight/pipeline/potato/colour_fit.hpp"
#include "cropsight/pipeline/potato/detection_eval.hpp"
#include "cropsight/pipeline/potato/orientation_dataset.hpp"

namespace {
using namespace cropsight;

void report(const char* name, const ColorImage& im, const std::vector<std::array<double, 4>>& boxes) {
  cv::Mat rgb(im.height, im.width, CV_8UC3, const_cast<Rgb8*>(im.data.data())), lab;
  cv::cvtColor(rgb, lab, cv::COLOR_RGB2Lab);
  cv::Mat inside(im.height, im.width, CV_8U, cv::Scalar(0));
  double sa = 0, sb = 0, sl = 0;
  int n = 0;
  for (const auto& b : boxes) {
    const cv::Point c(int((b[0] + b[2]) / 2), int((b[1] + b[3]) / 2));
    const cv::Size ax(int((b[2] - b[0]) * 0.35), int((b[3] - b[1]) * 0.35));
    cv::Mat e(im.height, im.width, CV_8U, cv::Scalar(0));
    cv::ellipse(e, c, ax, 0, 0, 360, cv::Scalar(255), cv::FILLED);
    cv::rectangle(inside, {int(b[0]), int(b[1])}, {int(b[2]), int(b[3])}, cv::Scalar(255), cv::FILLED);
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        if (e.at<uchar>(y, x)) {
          const auto p = lab.at<cv::Vec3b>(y, x);
          sl += p[0], sa += p[1], sb += p[2], ++n;
        }
  }
  std::vector<double> L, A, B;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      if (!inside.at<uchar>(y, x)) {
        const auto p = lab.at<cv::Vec3b>(y, x);
        L.push_back(p[0]), A.push_back(p[1]), B.push_back(p[2]);
      }
  // Bright background: pixels at or above the 75th percentile of L outside the boxes.
  std::vector<double> Ls = L;
  std::sort(Ls.begin(), Ls.end());
  const double l75 = Ls[Ls.size() * 3 / 4];
  std::vector<double> Ab, Bb;
  for (std::size_t i = 0; i < L.size(); ++i)
    if (L[i] >= l75) Ab.push_back(A[i]), Bb.push_back(B[i]);
  std::printf(
      "%-44s potato L %5.1f a %5.1f b %5.1f | median L %5.1f a %5.1f b %5.1f | bright L>=%3.0f a %5.1f b %5.1f\n", name,
      sl / std::max(n, 1), sa / std::max(n, 1), sb / std::max(n, 1), median(L), median(A), median(B), l75, median(Ab),
      median(Bb));
}
}  // namespace

void print_fit(const char* name, const std::vector<ColorImage>& ims,
               const std::vector<std::vector<Detection2D>>& boxes) {
  std::vector<const ColorImage*> p;
  for (const auto& im : ims) p.push_back(&im);
  const auto f = pipeline::potato::fit_potato_colour(p, boxes);
  std::printf("fit %s: mean_a %.2f mean_b %.2f cov_aa %.2f cov_ab %.2f cov_bb %.2f (%lld px)\n", name, f.mean_a,
              f.mean_b, f.cov_aa, f.cov_ab, f.cov_bb, static_cast<long long>(f.pixels));
}

// Long on purpose: a probe whose modes (--orient, --lab, --fit, the default sweep) share one entry point.
int main(int argc, char** argv) {
  if (argc == 9 && std::string(argv[1]) == "--orient") {
    const auto im = io::read_color(argv[2]);
    const Detection2D box{float(std::atof(argv[3])),
                          float(std::atof(argv[4])),
                          float(std::atof(argv[5])),
                          float(std::atof(argv[6])),
                          0,
                          1.f};
    measure::OrientationConfig cfg;
    cfg.input = std::string(argv[7]) == "rgb" ? measure::OrientationInput::rgb : measure::OrientationInput::depth;
    const auto r = measure::estimate_orientation(im, box, cfg, argv[2]);
    std::printf("ok %d angle %.1f deg, mask %dx%d at (%d, %d)\n", int(r.ok), r.angle_rad * 180 / 3.14159265358979,
                r.mask.width, r.mask.height, r.roi_x, r.roi_y);
    io::check_output_file(argv[8], io::OutputPolicy{"potato_probe", true, {argv[2]}});  // never the image read
    io::write_atomic_with(argv[8], [&](const std::filesystem::path& tmp) {
      cv::imwrite(tmp.string(),
                  cv::Mat(r.mask.height, r.mask.width, CV_8UC1, const_cast<std::uint8_t*>(r.mask.data.data())));
    });
    return 0;
  }
  if (argc >= 5 && std::string(argv[1]) == "--lab") {  // --lab IMAGE x y [x y ...]: Lab of 5x5 means at points
    const auto im = io::read_color(argv[2]);
    cv::Mat lab;
    cv::cvtColor(cv::Mat(im.height, im.width, CV_8UC3, const_cast<Rgb8*>(im.data.data())), lab, cv::COLOR_RGB2Lab);
    for (int i = 3; i + 1 < argc; i += 2) {
      const cv::Scalar m = cv::mean(lab(cv::Rect(std::atoi(argv[i]) - 2, std::atoi(argv[i + 1]) - 2, 5, 5)));
      const double chroma = std::hypot(m[1] - 128, m[2] - 128);
      std::printf("(%s, %s): L %.0f a %.0f b %.0f chroma %.1f saturation %.2f\n", argv[i], argv[i + 1], m[0], m[1],
                  m[2], chroma, chroma / std::max(1.0, m[0]));
    }
    return 0;
  }
  if (argc == 4 && std::string(argv[1]) == "--fit") {  // --fit IMAGES ANNOTATIONS: the colour fit of one VOC set
    std::vector<ColorImage> ims;
    std::vector<std::vector<Detection2D>> boxes;
    for (const auto& a : pipeline::potato::load_annotated_images(argv[2], argv[3])) {
      ims.push_back(io::read_color(a.image));
      boxes.emplace_back();
      for (const auto& b : pipeline::potato::truth_boxes(a.truth))
        boxes.back().push_back(Detection2D{float(b.x1), float(b.y1), float(b.x2), float(b.y2), 0, 1.f});
    }
    print_fit(argv[3], ims, boxes);
    return 0;
  }
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: %s DETECTION_DIR ORIENTATION_DIR [OVERLAY_DIR] | --fit IMAGES ANNOTATIONS\n", argv[0]);
    return 2;
  }
  const std::filesystem::path det = argv[1], ori = argv[2];
  for (const auto& a : pipeline::potato::load_annotated_images(det / "images", det / "annotations_voc")) {
    std::vector<std::array<double, 4>> boxes;
    for (const auto& b : pipeline::potato::truth_boxes(a.truth)) boxes.push_back({b.x1, b.y1, b.x2, b.y2});
    report(a.stem.substr(0, 12).c_str(), io::read_color(a.image), boxes);
  }
  pipeline::potato::BoardBlobDetector board;
  // The overlay folder is written whole at the end, by the one output rule.
  std::optional<io::OutputFolder> overlays;
  if (argc > 3) overlays.emplace(argv[3], io::OutputPolicy{"potato_probe", true, {det, ori}});
  for (const auto& s : pipeline::potato::list_orientation_shots(ori / "rgb", ori / "depth")) {
    const auto im = io::read_color(s.rgb);
    const auto d = board.detect(DetectorInput{&im, nullptr});
    std::vector<std::array<double, 4>> boxes;
    if (!d.empty()) boxes.push_back({d[0].x1, d[0].y1, d[0].x2, d[0].y2});
    const std::string name = s.rgb.parent_path().filename().string() + "/" + s.rgb.filename().string();
    report(name.c_str(), im, boxes);
    if (d.empty()) continue;
    std::printf("    box %.0f %.0f %.0f %.0f\n", d[0].x1, d[0].y1, d[0].x2, d[0].y2);
    if (overlays) {  // an overlay with a 10 px grid, for checking boxes by eye
      cv::Mat bgr;
      cv::cvtColor(cv::Mat(im.height, im.width, CV_8UC3, const_cast<Rgb8*>(im.data.data())), bgr, cv::COLOR_RGB2BGR);
      for (int x = 200; x < 460; x += 10) cv::line(bgr, {x, 150}, {x, x % 50 ? 155 : 165}, cv::Scalar(0, 0, 255));
      for (int y = 150; y < 360; y += 10) cv::line(bgr, {200, y}, {y % 50 ? 205 : 215, y}, cv::Scalar(0, 0, 255));
      cv::rectangle(bgr, {int(d[0].x1), int(d[0].y1)}, {int(d[0].x2), int(d[0].y2)}, cv::Scalar(0, 255, 0));
      const cv::Rect roi(200, 150, 260, 210);
      cv::Mat big;
      cv::resize(bgr(roi), big, {}, 2.5, 2.5, cv::INTER_NEAREST);
      cv::imwrite((overlays->path() / (std::to_string(s.number) + ".png")).string(), big);
    }
  }
  if (overlays) overlays->commit("overlays");
}
