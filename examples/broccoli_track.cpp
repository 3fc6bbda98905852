// cropsight as a library, end to end: detect broccoli heads in a recorded RGB-D sequence with a
// shipped model, size and track them (Kusumam et al. §4.4-4.5), and print the field map.
//
//   example_broccoli_track SEQUENCE_DIR MODEL.json
//
// SEQUENCE_DIR is a sequence in cropsight's format (docs/formats.md; `cropsight simulate broccoli`
// writes one), MODEL.json a broccoli model (models/broccoli-oes-uk.json). docs/library.md shows
// how to build this against cropsight from another CMake project.
#include <cstdio>
#include <memory>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli_detector.hpp"
#include "cropsight/pipeline/broccoli_training.hpp"
#include "cropsight/tracking/head_mapper.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SEQUENCE_DIR MODEL.json\n", argv[0]);
    return 2;
  }
  using namespace cropsight;
  try {
    // The model records the pipeline (OES / ORG / FEC), its parameters and the classifier.
    auto model = std::make_shared<learning::Model>(learning::load_model(argv[2]));
    pipeline::BroccoliDetector detector(pipeline::config_for_model(*model, /*overrides=*/{}, argv[2]));
    detector.set_model(model, argv[2]);

    // Sizing and tracking: the paper's defaults; any field can be set here (or from a preset with
    // HeadMapperConfig::apply). Poses from the sequence's poses.csv replace the estimated motion.
    tracking::HeadMapperConfig mapping;
    mapping.tracking.use_poses = true;
    tracking::HeadMapper mapper(mapping);

    const io::SequenceReader sequence(argv[1]);
    for (int i = 0; i < sequence.size(); ++i) {
      const RgbdFrame frame = sequence.read(i);
      detector.process(frame);  // one detector per thread: it reuses its buffers frame to frame
      std::vector<Detection> heads = detector.detections();
      mapper.add_frame(frame.index, detector.cloud(), heads, frame.camera_position);
      std::printf("frame %d: %zu heads", frame.index, heads.size());
      for (const Detection& h : heads)
        std::printf("  [track %d, score %.2f, %.0f mm, %.2f m away]", h.track_id, h.score, 1000.0 * h.size_m,
                    h.centroid.z());
      std::printf("\n");
    }
    const std::vector<tracking::TrackedHead>& map = mapper.finish();
    std::printf("field map: %zu heads\n", map.size());
    for (const auto& h : map) {
      std::printf("  head %d at x %.3f y %.3f m (field frame), seen in %d frames: ", h.id, h.position.x(),
                  h.position.y(), h.frames_seen);
      if (h.size_samples > 0)
        std::printf("%.0f mm%s\n", h.diameter_mm, h.harvestable ? ", harvestable" : "");
      else
        std::printf("not sized (only seen cut by the image border)\n");
    }
    return 0;
  } catch (const Error& e) {  // every bad input (file, format, value) is an Error naming it
    std::fprintf(stderr, "example_broccoli_track: %s\n", e.what());
    return 2;
  }
}
