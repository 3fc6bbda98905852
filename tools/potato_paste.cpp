// Training-set builder: cut-and-paste of the real potatoes of a VOC set onto the same
// images with their potatoes painted out, written as COCO instance annotations with polygon masks,
// so that `cropsight train detector --coco` learns from more than the few labelled images (and its
// copy-paste augmentation pastes through masks). Dwibedi et al. 2017, "Cut, Paste and Learn".
//
// Per labelled box: GrabCut (OpenCV, initialised with the box widened by 3 px) gives the potato's
// mask; a mask under 30 % or over 97 % of its box falls back to the box's inscribed ellipse.
// Backgrounds: each image with every potato mask (dilated 4 px) inpainted (Telea). A composite: a
// background, zoomed 1-1.4x at a random place, flipped half the time, gain 0.7-1.3 and offset
// +-20; then 1-5 potatoes of any source image, scaled 0.6-1.6, rotated +-25 deg, flipped, gain
// 0.6-1.2, each pasted through its feathered mask; 30 % of them overlap the previous one by a
// third to two thirds of its size (the overlapping pairs of the real set). A potato keeps its
// amodal box (as the VOC sets label overlapping potatoes) and is written only while at least half
// of it stays visible; otherwise the paste is undone and tried elsewhere.
// The source images themselves are written too, with their GrabCut masks.
//
// Usage: potato_paste --images DIR --voc DIR --out DIR [--count 300] [--seed 1] [--exclude a,b]
//   --exclude: image stems left out (a held-out fold); the output is DIR/annotations.json and
//   DIR/*.jpg. Deterministic for a seed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "coco_polygons.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/nn/detection_dataset.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct Sprite {
  cv::Mat bgr, mask;  // the box's pixels and its potato mask (0 / 255)
};

struct Source {
  std::string stem;
  cv::Mat bgr, background;
  std::vector<cv::Rect> boxes;
  std::vector<cv::Mat> masks;  // image-sized, one per box
};

cv::Mat potato_mask(const cv::Mat& bgr, const cv::Rect& box) {
  const cv::Rect all(0, 0, bgr.cols, bgr.rows);
  const cv::Rect wide = cv::Rect(box.x - 3, box.y - 3, box.width + 6, box.height + 6) & all;
  cv::Mat gc(bgr.size(), CV_8U, cv::Scalar(cv::GC_BGD)), bgd, fgd;
  cv::Mat mask(bgr.size(), CV_8U, cv::Scalar(0));
  try {
    cv::grabCut(bgr, gc, wide, bgd, fgd, 5, cv::GC_INIT_WITH_RECT);
    mask = ((gc == cv::GC_FGD) | (gc == cv::GC_PR_FGD)) & 255;
  } catch (const cv::Exception&) {
  }
  cv::Mat in_box(bgr.size(), CV_8U, cv::Scalar(0));
  in_box(box & all).setTo(255);
  mask &= in_box;
  const double fraction = cv::countNonZero(mask) / double(std::max(1, (box & all).area()));
  if (fraction < 0.30 || fraction > 0.97) {
    mask.setTo(0);
    cv::ellipse(mask, cv::Point(box.x + box.width / 2, box.y + box.height / 2), cv::Size(box.width / 2, box.height / 2),
                0, 0, 360, cv::Scalar(255), cv::FILLED);
  }
  return mask;
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string t; std::getline(ss, t, ',');)
    if (!t.empty()) out.push_back(t);
  return out;
}

struct Writer {
  fs::path dir;
  json images = json::array(), annotations = json::array();
  int next_ann = 1;

  void add(const std::string& name, const cv::Mat& bgr, const std::vector<cv::Rect>& boxes,
           const std::vector<cv::Mat>& visible) {
    const int id = int(images.size()) + 1;
    if (!cv::imwrite((dir / name).string(), bgr, {cv::IMWRITE_JPEG_QUALITY, 95}))
      throw std::runtime_error((dir / name).string() + ": cannot write");
    images.push_back({{"id", id}, {"file_name", name}, {"width", bgr.cols}, {"height", bgr.rows}});
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const auto& b = boxes[i];
      annotations.push_back({{"id", next_ann++},
                             {"image_id", id},
                             {"category_id", 1},
                             {"bbox", {b.x, b.y, b.width, b.height}},
                             {"area", double(cv::countNonZero(visible[i]))},
                             {"iscrowd", 0},
                             {"segmentation", cropsight::tools::coco_polygons(visible[i])}});
    }
  }
};

}  // namespace

// Long on purpose: a data tool read top to bottom: options, sources and their masks, the composites, the annotations.
int main(int argc, char** argv) {
  std::string images, voc, out, exclude;
  int count = 300;
  unsigned seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--images")
      images = v;
    else if (k == "--voc")
      voc = v;
    else if (k == "--out")
      out = v;
    else if (k == "--exclude")
      exclude = v;
    else if (k == "--count")
      count = std::stoi(v);
    else if (k == "--seed")
      seed = unsigned(std::stoul(v));
    else {
      std::fprintf(stderr, "potato_paste: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  if (images.empty() || voc.empty() || out.empty()) {
    std::fprintf(stderr,
                 "usage: potato_paste --images DIR --voc DIR --out DIR [--count N] [--seed S] [--exclude a,b]\n");
    return 2;
  }
  try {
    const auto left_out = split_list(exclude);
    const std::set<std::string> skip(left_out.begin(), left_out.end());
    const auto set = cropsight::nn::read_voc_detection(voc, images, {"potato"});
    std::vector<Source> sources;
    std::vector<Sprite> sprites;
    for (const auto& s : set.samples) {
      const std::string stem = fs::path(s.name).stem().string();
      if (skip.count(stem)) continue;
      Source src;
      src.stem = stem;
      cv::Mat rgb(s.image.height, s.image.width, CV_8UC3,
                  const_cast<void*>(static_cast<const void*>(s.image.data.data())));
      cv::cvtColor(rgb, src.bgr, cv::COLOR_RGB2BGR);
      cv::Mat all_masks(src.bgr.size(), CV_8U, cv::Scalar(0));
      for (const auto& d : s.boxes) {
        const cv::Rect box(cv::Point(int(std::floor(d.x1)), int(std::floor(d.y1))),
                           cv::Point(int(std::ceil(d.x2)), int(std::ceil(d.y2))));
        const cv::Rect clipped = box & cv::Rect(0, 0, src.bgr.cols, src.bgr.rows);
        if (clipped.area() < 16) continue;
        src.boxes.push_back(clipped);
        src.masks.push_back(potato_mask(src.bgr, clipped));
        all_masks |= src.masks.back();
        sprites.push_back({src.bgr(clipped).clone(), src.masks.back()(clipped).clone()});
      }
      cv::dilate(all_masks, all_masks, cv::getStructuringElement(cv::MORPH_ELLIPSE, {9, 9}));
      cv::inpaint(src.bgr, all_masks, src.background, 5, cv::INPAINT_TELEA);
      sources.push_back(std::move(src));
    }
    if (sources.empty() || sprites.empty()) throw std::runtime_error(voc + ": no labelled potato left");
    cropsight::io::OutputFolder folder(out, {"potato_paste", false, {images, voc}});
    Writer w{folder.path()};
    for (const auto& s : sources) w.add("real_" + s.stem + ".jpg", s.bgr, s.boxes, s.masks);

    std::mt19937 rng(seed);
    auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
    auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
    for (int n = 0; n < count; ++n) {
      const Source& bg = sources[pick(sources.size())];
      const cv::Size size = bg.background.size();
      const double zoom = uni(1.0, 1.4);
      const int cw = int(size.width / zoom), ch = int(size.height / zoom);
      const cv::Rect crop(int(uni(0, size.width - cw)), int(uni(0, size.height - ch)), cw, ch);
      cv::Mat canvas;
      cv::resize(bg.background(crop), canvas, size, 0, 0, cv::INTER_LINEAR);
      if (uni(0, 1) < 0.5) cv::flip(canvas, canvas, 1);
      canvas.convertTo(canvas, -1, uni(0.7, 1.3), uni(-20, 20));

      std::vector<cv::Rect> boxes;
      std::vector<cv::Mat> full;                    // each potato's whole mask, image-sized
      cv::Mat owner(size, CV_32S, cv::Scalar(-1));  // which potato each pixel shows
      const int potatoes = 1 + int(pick(5));
      for (int p = 0; p < potatoes; ++p) {
        const Sprite& sp = sprites[pick(sprites.size())];
        const double scale = uni(0.6, 1.6), angle = uni(-25, 25);
        cv::Mat img, mask;
        cv::resize(sp.bgr, img, {}, scale, scale, cv::INTER_LINEAR);
        cv::resize(sp.mask, mask, img.size(), 0, 0, cv::INTER_NEAREST);
        if (uni(0, 1) < 0.5) cv::flip(img, img, 1), cv::flip(mask, mask, 1);
        const int side = int(std::ceil(std::hypot(img.cols, img.rows))) + 2;
        cv::Mat rot = cv::getRotationMatrix2D({img.cols / 2.f, img.rows / 2.f}, angle, 1.0);
        rot.at<double>(0, 2) += (side - img.cols) / 2.0, rot.at<double>(1, 2) += (side - img.rows) / 2.0;
        cv::warpAffine(img, img, rot, {side, side}, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        cv::warpAffine(mask, mask, rot, {side, side}, cv::INTER_NEAREST);
        img.convertTo(img, -1, uni(0.6, 1.2), 0);
        const cv::Rect tight = cv::boundingRect(mask);
        if (tight.width < 6 || tight.height < 6) continue;
        img = img(tight).clone(), mask = mask(tight).clone();

        for (int attempt = 0; attempt < 20; ++attempt) {
          cv::Point at;
          if (!boxes.empty() && uni(0, 1) < 0.3) {
            const cv::Rect& prev = boxes.back();
            const double f = uni(0.33, 0.67), dir = uni(0, 2 * M_PI);
            at = {int(prev.x + prev.width / 2 + std::cos(dir) * f * prev.width - mask.cols / 2),
                  int(prev.y + prev.height / 2 + std::sin(dir) * f * prev.height - mask.rows / 2)};
          } else {
            at = {int(uni(-mask.cols / 4.0, size.width - 3 * mask.cols / 4.0)),
                  int(uni(-mask.rows / 4.0, size.height - 3 * mask.rows / 4.0))};
          }
          const cv::Rect place(at, mask.size());
          const cv::Rect inside = place & cv::Rect({0, 0}, size);
          if (inside.width < 6 || inside.height < 6) continue;
          cv::Mat whole(size, CV_8U, cv::Scalar(0));
          mask(cv::Rect(inside.tl() - place.tl(), inside.size())).copyTo(whole(inside));
          if (cv::countNonZero(whole) < 0.6 * cv::countNonZero(mask)) continue;
          // Every potato already placed must keep half of its mask visible.
          cv::Mat new_owner = owner.clone();
          new_owner.setTo(int(boxes.size()), whole);
          bool keeps = true;
          for (std::size_t q = 0; q < full.size() && keeps; ++q)
            keeps = cv::countNonZero(new_owner == int(q)) >= 0.5 * cv::countNonZero(full[q]);
          if (!keeps) continue;
          // Paste through the feathered mask.
          cv::Mat alpha;
          whole.convertTo(alpha, CV_32F, 1.0 / 255);
          cv::GaussianBlur(alpha, alpha, {3, 3}, 0);
          cv::Mat layer(size, CV_8UC3, cv::Scalar(0, 0, 0));
          img(cv::Rect(inside.tl() - place.tl(), inside.size())).copyTo(layer(inside));
          for (int y = inside.y; y < inside.y + inside.height; ++y)
            for (int x = inside.x; x < inside.x + inside.width; ++x) {
              const float a = alpha.at<float>(y, x);
              if (a <= 0) continue;
              auto& c = canvas.at<cv::Vec3b>(y, x);
              const auto& l = layer.at<cv::Vec3b>(y, x);
              for (int k = 0; k < 3; ++k) c[k] = cv::saturate_cast<uchar>(a * l[k] + (1 - a) * c[k]);
            }
          owner = new_owner;
          boxes.push_back(inside);
          full.push_back(whole);
          break;
        }
      }
      std::vector<cv::Mat> visible;
      for (std::size_t q = 0; q < full.size(); ++q) visible.push_back((owner == int(q)) & 255);
      char name[32];
      std::snprintf(name, sizeof name, "paste_%05d.jpg", n);
      w.add(name, canvas, boxes, visible);
      if ((n + 1) % 50 == 0) std::fprintf(stderr, "potato_paste: %d of %d composites\n", n + 1, count);
    }
    json coco = {{"images", w.images},
                 {"annotations", w.annotations},
                 {"categories", json::array({{{"id", 1}, {"name", "potato"}}})}};
    cropsight::io::write_file_atomic(folder.path() / "annotations.json", coco.dump());
    folder.commit("composites");
    std::printf("%zu source images, %zu potatoes, %d composites -> %s\n", sources.size(), sprites.size(), count,
                (fs::path(out) / "annotations.json").c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "potato_paste: %s\n", e.what());
    return 2;
  }
  return 0;
}
