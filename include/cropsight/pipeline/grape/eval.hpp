#pragma once
// Figures of a grape segmentation model on labelled clouds it was not trained on: the
// paper's OAcc / mAcc / mIoU, per-class accuracy and IoU (labels 0-5), the time per cloud, and
// mIoU under the named protocols below, so that a figure is compared with the paper's under
// the protocol it was measured with.
//
// Protocols (docs/pipelines/grape-bunches.md, "Figures protocols"):
// - pooled, all labels: one confusion matrix over every point of every cloud, IoU per label
//   0-5, mean over the labels (the `miou` this project has always reported);
// - pooled, named classes: the same matrix, mean over the classes the paper names (grape 1,
//   peduncle 2, leaf 3, background 4, noise 5). Label 0 is left out rather than merged with
//   background 4: in every one of the 96 shared clouds all of its points (19 % of all points)
//   sit at one identical xyz where no other label is - one location, not a surface of the scene
//   (most likely pixels without a valid depth) - while every label-4 point has a position of its
//   own. Every model scores label 0 exactly; merged, it would only lift background's IoU;
// - per cloud (ShapeNet-style, as the PointNet++ part-segmentation code the paper builds on):
//   per cloud IoU per class, a class absent from both truth and prediction counting 1; mean over
//   the classes, then over the clouds. Reported over the named classes and over all labels.
#include <functional>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/eval/segmentation_metrics.hpp"
#include "cropsight/pipeline/grape/model.hpp"
#include "cropsight/pipeline/grape/truth.hpp"

namespace cropsight::pipeline::grape {

/// Mean IoU over `classes` of a pooled confusion matrix; classes with undefined IoU (in neither
/// truth nor prediction) are skipped, as ConfusionMatrix::mean_iou(). NaN when none is defined.
/// Ids outside the matrix throw Error.
double pooled_miou(const eval::ConfusionMatrix& confusion, const std::vector<int>& classes);

/// ShapeNet-style mIoU: for each cloud's confusion matrix the mean over `classes` of the IoU, a
/// class absent from both its truth and its prediction counting 1; then the mean over clouds.
/// NaN for no cloud. Ids outside a matrix throw Error.
double per_cloud_miou(const std::vector<eval::ConfusionMatrix>& clouds, const std::vector<int>& classes);

struct Figures {
  eval::ConfusionMatrix confusion{6};
  std::vector<eval::ConfusionMatrix> per_cloud;  ///< one matrix per evaluated cloud, in order
  std::size_t clouds = 0;
  std::size_t points = 0;
  double seconds = 0;  ///< wall time of segment() summed over clouds (features + inference)

  double ms_per_cloud() const { return clouds ? 1000.0 * seconds / double(clouds) : 0.0; }
  /// Label ids 0..num_classes-1.
  std::vector<int> all_labels() const;
  /// The named classes that exist in this evaluation's label range.
  std::vector<int> named_classes() const;
  void merge(const Figures& o);
  /// Human-readable summary (several lines). The CLI's JSON form is apps/cropsight/grape_cli.hpp.
  std::string text() const;
};

/// One of the mIoU protocols above, as measured on an evaluation.
struct Protocol {
  std::string name;          ///< key: "pooled_all_labels", "pooled_named_classes", ...
  std::string label;         ///< in words: "pooled, all labels", ...
  std::vector<int> classes;  ///< the label ids averaged over
  double miou = 0;           ///< NaN when undefined
};

/// The four protocols, in the order above: pooled all labels (= confusion.mean_iou()), pooled
/// named classes, per cloud named classes, per cloud all labels.
std::vector<Protocol> grape_protocols(const Figures& e);

/// Accumulates the confusion matrices of segmented clouds, pooled and per cloud.
class Evaluator {
 public:
  explicit Evaluator(int num_classes = 6);
  /// One cloud: `predicted` (a label per point) against `truth`'s own labels; `seconds` the time
  /// its segmentation took. Throws Error when the cloud has no labels, the sizes differ, or a
  /// label is >= num_classes.
  void add(const std::vector<int>& predicted, const Cloud& truth, double seconds = 0);
  const Figures& figures() const { return figures_; }

 private:
  Figures figures_;
};

/// Segments each cloud with `model` (timed) and accumulates the confusion matrix against the
/// clouds' labels, pooled and per cloud. Labels >= num_classes throw Error.
Figures evaluate_grape(const Model& model, const std::vector<Cloud>& clouds, int num_classes = 6);

}  // namespace cropsight::pipeline::grape
