// cropsight as a library, end to end: detect broccoli heads in a recorded RGB-D sequence with a
// shipped model, size and track them (Kusumam et al. §4.4-4.5), print the field map and, when the
// sequence has ground truth, the headline figures the CLI's `eval broccoli --track` prints.
//
//   example_broccoli_track SEQUENCE_DIR MODEL.json
//
// SEQUENCE_DIR is a sequence in cropsight's format (docs/formats.md; `cropsight simulate broccoli`
// writes one), MODEL.json a broccoli model (models/broccoli-oes-uk.json). On the documented test
// pass (`cropsight simulate broccoli --variety uk --seed 2001 --frames 50`) it prints the figures
// of docs/pipelines/broccoli-heads.md and broccoli-sizing-tracking.md (kappa 0.951, AP50 0.815,
// 0.980 on visible heads, 0.8475 with the temporal filter after the pass). docs/library.md shows
// how to build this against cropsight from another CMake project.
#include <cstdio>
#include <optional>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/eval.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SEQUENCE_DIR MODEL.json\n", argv[0]);
    return 2;
  }
  using namespace cropsight;
  try {
    // One config: what the model records (variant, parameters, classifier) ← any overrides; here
    // the camera positions of poses.csv replace the estimated motion. One call builds it, as the
    // CLI and the ROS node do.
    const auto built = pipeline::broccoli::make_pipeline({.sets = {"tracking.use_poses=true"}, .model = argv[2]});
    pipeline::broccoli::Pipeline& broccoli = *built;

    const io::SequenceReader sequence(argv[1]);
    const bool labelled = sequence.info().has_labels && sequence.info().has_groundtruth;
    std::optional<pipeline::broccoli::Evaluator> detection;  // Table I / II of Montes et al.
    std::optional<pipeline::broccoli::TrackingEvaluator> tracking;
    if (labelled) {
      detection.emplace(broccoli);
      tracking.emplace();
      tracking->begin_pass(sequence.groundtruth(), !sequence.poses().empty(), argv[1]);
    }
    for (int i = 0; i < sequence.size(); ++i) {
      const RgbdFrame frame = sequence.read(i);
      // process(): detect, size, track, predict missed heads (the evaluator calls it when labelled)
      if (detection)
        detection->add_frame(frame);
      else
        broccoli.process(frame);
      const pipeline::broccoli::FrameResult& r = broccoli.last();
      if (tracking) tracking->add_frame(frame, broccoli);
      std::printf("frame %d: %zu heads", frame.index, r.detections.size());
      for (const Detection& h : r.detections)
        std::printf("  [track %d, score %.2f, %.0f mm, %.2f m away]", h.track_id, h.score, 1000.0 * h.size_m,
                    h.centroid.z());
      std::printf("\n");
    }
    if (tracking) tracking->end_pass(broccoli);  // ends the pass itself (the map)
    const auto& map = tracking ? broccoli.mapper().map() : broccoli.finish();
    std::printf("field map: %zu heads\n", map.size());
    for (const auto& h : map) {
      std::printf("  head %d at x %.3f y %.3f m (field frame), seen in %d frames: ", h.id, h.position.x(),
                  h.position.y(), h.frames_seen);
      if (h.size_samples > 0)
        std::printf("%.0f mm%s\n", h.diameter_mm, h.harvestable ? ", harvestable" : "");
      else
        std::printf("not sized (only seen cut by the image border)\n");
    }
    if (labelled) {
      const auto d = detection->figures();
      const auto t = tracking->figures();
      std::printf("kappa %.3f  AP50 %.3f  AP50 visible heads %.3f\n", d.confusion.kappa(), d.ap50, d.ap50_visible);
      std::printf("AP50 with the temporal filter: online %.4f  offline %.4f\n", t.ap50_online, t.ap50_offline);
      std::printf("map precision %.3f  recall %.3f  size MEDE %.1f mm  MAD %.1f mm  r %.3f (%d heads)\n",
                  t.map_precision, t.map_recall, t.head_size.mede_mm, t.head_size.mad_mm, t.head_size.pearson_r,
                  t.head_size.n);
    }
    return 0;
  } catch (const Error& e) {  // every bad input (file, format, value) is an Error naming it
    std::fprintf(stderr, "example_broccoli_track: %s\n", e.what());
    return 2;
  }
}
