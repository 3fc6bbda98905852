#include "report_cli.hpp"

#include "broccoli_cli.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/broccoli_report_data.hpp"
#include "cropsight/report/broccoli_run_data.hpp"
#include "cropsight/report/sequence_page.hpp"

namespace cropsight::cli {

namespace {

// A sequence without ground truth (a user's own recording): what the pipeline found, no metric.
BroccoliReportPass unlabelled_pass(const io::SequenceReader& reader, pipeline::broccoli::Pipeline& pipe,
                                   const std::string& seq, const std::string& model, int overlay_frames,
                                   Progress& progress) {
  report::BroccoliRunRecorder recorder(report::evenly_spaced_frames(reader.size(), overlay_frames));
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame frame = reader.read(i);
    recorder.add_frame(frame, pipe.process(frame));
    progress.update(i + 1);
  }
  progress.finish();
  const std::vector<tracking::TrackedHead> map = pipe.finish();
  return {std::nullopt,
          recorder.finish(map, pipe.detector().timer().stages(), seq, model, pipe.config().sizing.estimator)};
}

}  // namespace

BroccoliReportPass broccoli_report_pass(const std::string& seq, const std::string& model, const CommonOptions& common,
                                        int overlay_frames, bool quiet) {
  const auto built = make_broccoli(model, common, /*track=*/true);
  pipeline::broccoli::Pipeline& pipe = *built;
  io::SequenceReader reader(seq);
  Progress progress("report broccoli: " + seq, reader.size(), common.json || quiet);
  if (!reader.info().has_labels || !reader.info().has_groundtruth)
    return unlabelled_pass(reader, pipe, seq, model, overlay_frames, progress);
  pipeline::broccoli::TrackingEvaluator tracker(
      {.overlay_frames = report::evenly_spaced_frames(reader.size(), overlay_frames)});
  tracker.begin_pass(reader.groundtruth(), !reader.poses().empty(), seq);
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame frame = reader.read(i);
    pipe.process(frame);
    tracker.add_frame(frame, pipe);
    progress.update(i + 1);
  }
  progress.finish();
  tracker.end_pass(pipe);
  BroccoliReportPass pass{tracker.figures(), {}};
  pass.data = report::broccoli_report_data(*pass.figures, tracker.material());
  pass.data.model = model;
  pass.data.stages = pipe.detector().timer().stages();
  return pass;
}

}  // namespace cropsight::cli
