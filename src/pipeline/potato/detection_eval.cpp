// The folder walk and conversions of `eval potato-detection`; the metric is eval/voc_ap.
#include "cropsight/pipeline/potato/detection_eval.hpp"

#include <algorithm>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/image_io.hpp"

namespace cropsight::pipeline::potato {
namespace fs = std::filesystem;

std::vector<AnnotatedImage> load_annotated_images(const fs::path& images_dir, const fs::path& annotations_dir) {
  if (!fs::is_directory(annotations_dir)) throw Error(annotations_dir.string(), "not a folder of VOC annotations");
  if (!fs::is_directory(images_dir)) throw Error(images_dir.string(), "not a folder of images");
  std::vector<fs::path> xmls;
  for (const auto& e : fs::directory_iterator(annotations_dir))
    if (e.is_regular_file() && e.path().extension() == ".xml") xmls.push_back(e.path());
  if (xmls.empty()) throw Error(annotations_dir.string(), "holds no .xml annotation");
  std::sort(xmls.begin(), xmls.end());
  std::vector<AnnotatedImage> out;
  for (const fs::path& x : xmls) {
    AnnotatedImage a;
    a.truth = io::read_voc(x);
    a.stem = x.stem().string();
    std::vector<fs::path> candidates;
    if (!a.truth.filename.empty()) {
      // A relative path (<filename>0_high_rgb/image2.png</filename>) names an image in a subfolder.
      if (const fs::path f(a.truth.filename); f.is_relative() && f.has_parent_path())
        candidates.push_back(images_dir / f);
      candidates.push_back(images_dir / fs::path(a.truth.filename).filename());
    }
    candidates.push_back(images_dir / (a.stem + ".jpg"));
    candidates.push_back(images_dir / (a.stem + ".png"));
    for (const fs::path& c : candidates)
      if (fs::is_regular_file(c)) {
        a.image = c;
        break;
      }
    if (a.image.empty()) throw Error(candidates.front().string(), "image of annotation " + x.string() + " not found");
    out.push_back(std::move(a));
  }
  return out;
}

std::vector<eval::VocBox> truth_boxes(const io::VocAnnotation& a, const std::string& class_name) {
  std::vector<eval::VocBox> out;
  for (const io::VocObject& o : a.objects)
    if (o.name == class_name) out.push_back({o.xmin, o.ymin, o.xmax, o.ymax, 1.0});
  return out;
}

std::vector<eval::VocBox> detection_boxes(const std::vector<io::DetectionLine>& lines, const std::string& class_name) {
  std::vector<eval::VocBox> out;
  for (const io::DetectionLine& l : lines)
    if (l.label == class_name) out.push_back({l.x1, l.y1, l.x2, l.y2, l.score});
  return out;
}

std::vector<eval::VocBox> detection_boxes(const std::vector<Detection2D>& dets) {
  std::vector<eval::VocBox> out;
  for (const Detection2D& d : dets)
    if (d.class_id == 0) out.push_back({d.x1, d.y1, d.x2, d.y2, d.score});
  return out;
}

DetectionEvalResult evaluate_saved_detections(const std::vector<AnnotatedImage>& set, const fs::path& detections_dir,
                                              const std::string& class_name) {
  if (!fs::is_directory(detections_dir)) throw Error(detections_dir.string(), "not a folder of detection files");
  std::vector<eval::VocImage> images;
  for (const AnnotatedImage& a : set) {
    const fs::path file = detections_dir / (a.stem + ".txt");
    if (!fs::exists(file)) throw Error(file.string(), "detection file missing (one <stem>.txt per annotation)");
    images.push_back({truth_boxes(a.truth, class_name), detection_boxes(io::read_detection_text(file), class_name)});
  }
  return {eval::voc_ap_summary(images), 0.0};
}

DetectionEvalResult evaluate_detector(Detector2D& detector, const std::vector<AnnotatedImage>& set,
                                      const std::string& class_name) {
  std::vector<eval::VocImage> images;
  double ms = 0;
  bool warm = false;
  for (const AnnotatedImage& a : set) {
    const ColorImage img = io::read_color(a.image);
    // One untimed call first: OpenCV builds its colour-conversion tables on first use (~0.2 s),
    // a one-off cost of the process, not of an image.
    if (!warm) detector.detect({&img, nullptr}), warm = true;
    Stopwatch sw;
    const std::vector<Detection2D> dets = detector.detect({&img, nullptr});
    ms += sw.ms();
    images.push_back({truth_boxes(a.truth, class_name), detection_boxes(dets)});
  }
  return {eval::voc_ap_summary(images), set.empty() ? 0.0 : ms / double(set.size())};
}

}  // namespace cropsight::pipeline::potato
