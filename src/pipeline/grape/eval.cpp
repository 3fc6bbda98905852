#include "cropsight/pipeline/grape/eval.hpp"

#include <cmath>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"

namespace cropsight::pipeline::grape {

namespace {
void check_classes(const eval::ConfusionMatrix& m, const std::vector<int>& classes) {
  for (int c : classes)
    if (c < 0 || c >= m.num_classes())
      throw Error("grape evaluation", "class " + std::to_string(c) + " is not a label of a " +
                                          std::to_string(m.num_classes()) + "-class confusion matrix");
}
}  // namespace

double pooled_miou(const eval::ConfusionMatrix& confusion, const std::vector<int>& classes) {
  check_classes(confusion, classes);
  double sum = 0;
  int defined = 0;
  for (int c : classes) {
    const double iou = confusion.class_iou(c);
    if (std::isnan(iou)) continue;
    sum += iou;
    ++defined;
  }
  return defined ? sum / defined : std::nan("");
}

double per_cloud_miou(const std::vector<eval::ConfusionMatrix>& clouds, const std::vector<int>& classes) {
  if (clouds.empty() || classes.empty()) return std::nan("");
  double sum = 0;
  for (const auto& m : clouds) {
    check_classes(m, classes);
    double cloud = 0;
    for (int c : classes) {
      const double iou = m.class_iou(c);
      cloud += std::isnan(iou) ? 1.0 : iou;  // absent from truth and prediction: nothing to get wrong
    }
    sum += cloud / double(classes.size());
  }
  return sum / double(clouds.size());
}

std::vector<int> Figures::all_labels() const {
  std::vector<int> out(std::size_t(confusion.num_classes()));
  for (int c = 0; c < confusion.num_classes(); ++c) out[std::size_t(c)] = c;
  return out;
}

std::vector<int> Figures::named_classes() const {
  std::vector<int> out;
  for (int c : grape_named_classes())
    if (c < confusion.num_classes()) out.push_back(c);
  return out;
}

void Figures::merge(const Figures& o) {
  confusion.merge(o.confusion);
  per_cloud.insert(per_cloud.end(), o.per_cloud.begin(), o.per_cloud.end());
  clouds += o.clouds;
  points += o.points;
  seconds += o.seconds;
}

std::vector<Protocol> grape_protocols(const Figures& e) {
  const std::vector<int> all = e.all_labels(), named = e.named_classes();
  return {{"pooled_all_labels", "pooled, all labels", all, e.confusion.mean_iou()},
          {"pooled_named_classes", "pooled, named classes", named, pooled_miou(e.confusion, named)},
          {"per_cloud_named_classes", "per cloud, named classes", named, per_cloud_miou(e.per_cloud, named)},
          {"per_cloud_all_labels", "per cloud, all labels", all, per_cloud_miou(e.per_cloud, all)}};
}

std::string Figures::text() const {
  std::ostringstream o;
  o.precision(4);
  o << "clouds " << clouds << ", points " << points << "\n";
  o << "OAcc " << confusion.overall_accuracy() << "  mAcc " << confusion.mean_accuracy() << "  mIoU "
    << confusion.mean_iou() << "\n";
  for (int c = 0; c < confusion.num_classes(); ++c)
    o << "  label " << c << ": points " << confusion.truth_count(c) << "  acc " << confusion.class_accuracy(c)
      << "  IoU " << confusion.class_iou(c) << "\n";
  o << "mIoU by protocol:\n";
  for (const auto& p : grape_protocols(*this)) {
    o << "  " << p.label << " (";
    for (std::size_t i = 0; i < p.classes.size(); ++i) o << (i ? " " : "") << p.classes[i];
    o << "): " << p.miou << "\n";
  }
  o << "ms per cloud " << ms_per_cloud() << "\n";
  return o.str();
}

Evaluator::Evaluator(int num_classes) { figures_.confusion = eval::ConfusionMatrix(num_classes); }

void Evaluator::add(const std::vector<int>& predicted, const Cloud& truth, double seconds) {
  if (!truth.has_labels()) throw Error("eval grape", "cloud without labels");
  if (predicted.size() != truth.size()) throw Error("eval grape", "a label per point is needed");
  eval::ConfusionMatrix one(figures_.confusion.num_classes());
  one.add(truth.labels, predicted);
  figures_.confusion.merge(one);
  figures_.per_cloud.push_back(std::move(one));
  figures_.clouds += 1;
  figures_.points += truth.size();
  figures_.seconds += seconds;
}

Figures evaluate_grape(const Model& model, const std::vector<Cloud>& clouds, int num_classes) {
  Evaluator ev(num_classes);
  for (const auto& c : clouds) {
    if (!c.has_labels()) throw Error("eval grape", "cloud without labels");
    const Stopwatch clock;
    const std::vector<int> pred = model.segment(c);
    ev.add(pred, c, clock.seconds());
  }
  return ev.figures();
}

}  // namespace cropsight::pipeline::grape
