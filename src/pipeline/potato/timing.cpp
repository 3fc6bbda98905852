// Timing of the potato loop (see potato/timing.hpp).
#include "cropsight/pipeline/potato/timing.hpp"

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::potato {

namespace {
void check(const std::vector<RgbdFrame>& frames, int repeat) {
  if (frames.empty()) throw Error("bench potato", "no frames to time");
  if (repeat < 1) throw Error("bench potato", "repeat must be at least 1");
}

}  // namespace

PipelineTiming time_potato_pipeline(Pipeline& pipeline, const std::vector<RgbdFrame>& frames, int repeat) {
  check(frames, repeat);
  const OneOpenCvThread one_thread;
  pipeline.reset();
  pipeline.process(frames.front());  // warm-up: buffers sized, the tracker's first allocation
  PipelineTiming t;
  StageTimer stages;
  for (int r = 0; r < repeat; ++r) {
    pipeline.reset();
    for (const RgbdFrame& f : frames) {
      const FrameResult out = timed(t, [&] { return pipeline.process(f); });
      for (const StageTimer::Stage& s : out.timer.stages()) stages.add(s.name, s.total_ms);
      t.clusters += out.target.detection ? 1 : 0;
      ++t.frames;
    }
  }
  t.stages = stages.stages();
  return t;
}

PipelineTiming time_lab_conversion(const std::vector<RgbdFrame>& frames, int repeat) {
  check(frames, repeat);
  const OneOpenCvThread one_thread;
  PipelineTiming t;
  cv::Mat lab;
  // Warm-up, as the pipeline's: OpenCV builds its Lab tables on the first conversion (~50 ms).
  cv::cvtColor(stereo::detail::view(frames.front().color), lab, cv::COLOR_RGB2Lab);
  for (int r = 0; r < repeat; ++r)
    for (const RgbdFrame& f : frames) {
      const cv::Mat rgb = stereo::detail::view(f.color);  // no copy
      timed(t, [&] {
        cv::cvtColor(rgb, lab, cv::COLOR_RGB2Lab);
        return 0;
      });
      ++t.frames;
    }
  return t;
}

}  // namespace cropsight::pipeline::potato
