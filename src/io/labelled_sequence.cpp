// Image labels drawn on a depth sequence's frames into a new sequence that `train broccoli` reads
// (io/image_labels.hpp, write_labelled_sequence).
#include <algorithm>
#include <map>

#include "cropsight/core/error.hpp"
#include "cropsight/io/image_labels.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::io {

namespace labelled_sequence_detail {

// The labelled images by frame index, each checked against the sequence.
std::map<int, const ImageLabels*> frames_named(const SequenceReader& reader, const LabelSet& labels,
                                               const std::string& where) {
  std::map<int, const ImageLabels*> by_frame;
  for (const ImageLabels& im : labels.images) {
    const int f = frame_index_from_name(im.file_name);
    if (f < 0) throw Error(where, "image '" + im.file_name + "' has no frame number in its name");
    if (f >= reader.size())
      throw Error(where, "image '" + im.file_name + "' names frame " + std::to_string(f) + ", past the end of " +
                             reader.info().dir.string() + " (" + std::to_string(reader.size()) + " frames)");
    if (!by_frame.emplace(f, &im).second)
      throw Error(where, "frame " + std::to_string(f) + " is labelled twice ('" + im.file_name + "')");
    const auto& cam = reader.info().camera;
    if (im.width != cam.width || im.height != cam.height)
      throw Error(where, "image '" + im.file_name + "' is " + std::to_string(im.width) + "x" +
                             std::to_string(im.height) + " but the sequence's frames are " + std::to_string(cam.width) +
                             "x" + std::to_string(cam.height));
  }
  if (by_frame.empty()) throw Error(where, "labels no image");
  return by_frame;
}

ImageLabels of_classes(const ImageLabels& im, const std::vector<std::string>& classes) {
  if (classes.empty()) return im;
  ImageLabels kept = im;
  kept.shapes.clear();
  for (const LabelShape& s : im.shapes)
    if (std::find(classes.begin(), classes.end(), s.label) != classes.end()) kept.shapes.push_back(s);
  return kept;
}

}  // namespace labelled_sequence_detail

LabelledSequenceSummary write_labelled_sequence(const std::filesystem::path& sequence, const LabelSet& labels,
                                                const std::vector<std::string>& classes,
                                                const std::filesystem::path& out, const OutputPolicy& policy,
                                                const std::string& source) {
  using namespace labelled_sequence_detail;
  const SequenceReader reader(sequence);
  const auto by_frame = frames_named(reader, labels, source);
  SequenceWriter writer(out, reader.info().camera, policy);
  LabelledSequenceSummary summary;
  int next_id = 1;
  for (const auto& [f, im] : by_frame) {
    RgbdFrame frame = reader.read(f);
    const ImageLabels kept = of_classes(*im, classes);
    frame.labels = rasterise_instances(kept, next_id);
    next_id += int(kept.shapes.size());
    summary.instances += int(kept.shapes.size());
    frame.index = summary.frames++;
    summary.source_frames.push_back(f);
    writer.write(frame);
  }
  GroundTruth truth;
  std::string list;
  for (int f : summary.source_frames) list += (list.empty() ? "" : ",") + std::to_string(f);
  truth.attributes = {{"generator", "cropsight import"},
                      {"source", source},
                      {"sequence", sequence.string()},
                      {"source_frames", list},
                      {"instances", "2D labels: label images only, no field positions or sizes"}};
  writer.set_groundtruth(std::move(truth));
  writer.finish();
  return summary;
}

}  // namespace cropsight::io
