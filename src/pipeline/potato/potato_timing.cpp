// Timing of the potato loop (see potato_timing.hpp).
#include "cropsight/pipeline/potato/potato_timing.hpp"

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

// OpenCV's own thread pool on one thread while timing (the figures are single-threaded), restored
// afterwards.
class OneOpenCvThread {
 public:
  OneOpenCvThread() : before_(cv::getNumThreads()) { cv::setNumThreads(1); }
  ~OneOpenCvThread() { cv::setNumThreads(before_); }
  OneOpenCvThread(const OneOpenCvThread&) = delete;
  OneOpenCvThread& operator=(const OneOpenCvThread&) = delete;

 private:
  int before_;
};

void add_stage(PipelineTiming& t, const char* name, double ms) {
  for (auto& s : t.stages)
    if (s.name == name) {
      s.total_ms += ms;
      ++s.count;
      return;
    }
  t.stages.push_back({name, ms, 1});
}
}  // namespace

PipelineTiming time_potato_pipeline(PotatoPipeline& pipeline, const std::vector<RgbdFrame>& frames, int repeat) {
  check(frames, repeat);
  const OneOpenCvThread one_thread;
  pipeline.reset();
  pipeline.process(frames.front());  // warm-up: buffers sized, the tracker's first allocation
  PipelineTiming t;
  for (int r = 0; r < repeat; ++r) {
    pipeline.reset();
    for (const RgbdFrame& f : frames) {
      const PotatoFrameResult out = timed(t, [&] { return pipeline.process(f); });
      add_stage(t, "detect", out.ms_detect);
      add_stage(t, "locate", out.ms_locate);
      add_stage(t, "track", out.ms_track);
      add_stage(t, "orient", out.ms_orient);
      t.clusters += out.target.detection ? 1 : 0;
      ++t.frames;
    }
  }
  return t;
}

PipelineTiming time_lab_conversion(const std::vector<RgbdFrame>& frames, int repeat) {
  check(frames, repeat);
  const OneOpenCvThread one_thread;
  PipelineTiming t;
  cv::Mat lab;
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
