// cropsight as a library: segment grape bunch clouds into their parts with the shipped best recipe
// (PointResNet + fast GBDT ensemble, configs/grape-best.yaml) and score them against their labels.
//
//   example_grape_segment PRESET CLOUD_DIR [k/K]
//
// PRESET is a grape segmenter preset (configs/grape-best-fold1.yaml: the recipe with the models
// that never saw fold 1), CLOUD_DIR a folder of labelled text clouds (scripts/unpack-grape.sh
// unpacks the authors' clouds), k/K the fold of the by-cloud split to evaluate (default 1/4). With
// the fold-1 preset on fold 1 it prints the held-out figures of docs/pipelines/grape-bunches.md
// (pooled six-label mIoU 0.848, 0.818 over the named classes 1-5).
#include <cstdio>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape/eval.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"
#include "cropsight/pipeline/grape/truth.hpp"

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: %s PRESET CLOUD_DIR [k/K]\n", argv[0]);
    return 2;
  }
  using namespace cropsight;
  try {
    // One config from one preset: the models, the sampled pass, the votes, the ensemble weight.
    const pipeline::grape::Segmenter segmenter(pipeline::grape::load_segmenter_config(argv[1]), argv[1]);
    // The held-out clouds: the fold of the same seeded by-cloud split the models were trained on.
    const auto [k, K] = pipeline::grape::parse_fold(argc == 4 ? argv[3] : "1/4", "fold");
    const auto files = io::list_grape_clouds(argv[2]);
    const auto fold = pipeline::grape::grape_folds(files.size(), K);
    std::vector<std::filesystem::path> held_out;
    for (std::size_t i = 0; i < files.size(); ++i)
      if (fold[i] == k) held_out.push_back(files[i]);
    const auto clouds = pipeline::grape::load_grape_clouds(held_out);
    // segmenter.segment(cloud) labels one cloud; the evaluator does it for each and counts.
    const pipeline::grape::Figures ev = pipeline::grape::evaluate_grape(segmenter.model(), clouds);
    std::printf("%zu held-out clouds, %zu points, %.0f ms per cloud\n", ev.clouds, ev.points, ev.ms_per_cloud());
    std::printf("OAcc %.3f  mAcc %.3f  mIoU %.3f (pooled, six labels)\n", ev.confusion.overall_accuracy(),
                ev.confusion.mean_accuracy(), ev.confusion.mean_iou());
    std::printf("mIoU %.3f pooled over the named classes, %.3f per cloud\n",
                pipeline::grape::pooled_miou(ev.confusion, ev.named_classes()),
                pipeline::grape::per_cloud_miou(ev.per_cloud, ev.named_classes()));
    return 0;
  } catch (const Error& e) {  // every bad input (file, format, value) is an Error naming it
    std::fprintf(stderr, "example_grape_segment: %s\n", e.what());
    return 2;
  }
}
