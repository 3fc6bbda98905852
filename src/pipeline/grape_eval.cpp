#include "cropsight/pipeline/grape_eval.hpp"

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline {

namespace {
nlohmann::json num(double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); }
}  // namespace

void GrapeEvaluation::merge(const GrapeEvaluation& o) {
  confusion.merge(o.confusion);
  clouds += o.clouds;
  points += o.points;
  seconds += o.seconds;
}

std::string GrapeEvaluation::json() const {
  nlohmann::json j;
  j["clouds"] = clouds;
  j["points"] = points;
  j["oacc"] = num(confusion.overall_accuracy());
  j["macc"] = num(confusion.mean_accuracy());
  j["miou"] = num(confusion.mean_iou());
  j["per_class"] = nlohmann::json::array();
  for (int c = 0; c < confusion.num_classes(); ++c)
    j["per_class"].push_back({{"label", c},
                              {"points", confusion.truth_count(c)},
                              {"accuracy", num(confusion.class_accuracy(c))},
                              {"iou", num(confusion.class_iou(c))}});
  j["ms_per_cloud"] = ms_per_cloud();
  return j.dump();
}

std::string GrapeEvaluation::text() const {
  std::ostringstream o;
  o.precision(4);
  o << "clouds " << clouds << ", points " << points << "\n";
  o << "OAcc " << confusion.overall_accuracy() << "  mAcc " << confusion.mean_accuracy() << "  mIoU "
    << confusion.mean_iou() << "\n";
  for (int c = 0; c < confusion.num_classes(); ++c)
    o << "  label " << c << ": points " << confusion.truth_count(c) << "  acc " << confusion.class_accuracy(c)
      << "  IoU " << confusion.class_iou(c) << "\n";
  o << "ms per cloud " << ms_per_cloud() << "\n";
  return o.str();
}

GrapeEvaluation evaluate_grape(const GrapeModel& model, const std::vector<Cloud>& clouds, int num_classes) {
  GrapeEvaluation e;
  e.confusion = eval::ConfusionMatrix(num_classes);
  for (const auto& c : clouds) {
    if (!c.has_labels()) throw Error("eval grape", "cloud without labels");
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<int> pred = model.segment(c);
    e.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    e.confusion.add(c.labels, pred);
    e.clouds += 1;
    e.points += c.size();
  }
  return e;
}

}  // namespace cropsight::pipeline
