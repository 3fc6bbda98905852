#pragma once
// Timing of a pipeline as deployed, shared by the `cropsight bench` commands and library users who
// compare settings on their own frames: wall clock and this thread's CPU time over frames already
// in memory, and the per-stage totals. Call from a single-threaded section (the papers' figures
// are single-threaded; the CLI caps TBB to one thread) so that the CPU time is the pipeline's
// alone. Speed ratios between runs timed in the same process are the robust figures on a shared
// machine.
#include <vector>

#include "cropsight/core/timer.hpp"

namespace cropsight::pipeline {

struct PipelineTiming {
  double ms = 0;      ///< wall clock, total over the timed frames
  double cpu_ms = 0;  ///< thread CPU time, total
  long frames = 0;
  long clusters = 0;  ///< clusters / detections over the timed frames (what the pipeline counts)
  std::vector<StageTimer::Stage> stages;
  double ms_per_frame() const { return frames ? ms / double(frames) : 0.0; }
  double fps() const { return ms > 0 ? 1000.0 * double(frames) / ms : 0.0; }
  double cpu_ms_per_frame() const { return frames ? cpu_ms / double(frames) : 0.0; }
  double cpu_fps() const { return cpu_ms > 0 ? 1000.0 * double(frames) / cpu_ms : 0.0; }
  double clusters_per_frame() const { return frames ? double(clusters) / double(frames) : 0.0; }
  std::vector<StageMs> stage_ms_per_frame() const { return per_frame_ms(stages, frames); }
};

/// How many times one pipeline's time per frame is another's: the figure that holds on a shared
/// machine when both were timed in the same process.
struct SpeedRatio {
  double wall = 0.0;  ///< wall clock
  double cpu = 0.0;   ///< thread CPU time
};

/// `num`'s time per frame over `den`'s, wall clock and CPU each; 0 where `den` took no time.
SpeedRatio time_ratio(const PipelineTiming& num, const PipelineTiming& den);

/// CPU time of the calling thread, ms: on a shared machine it counts only the cycles the pipeline
/// itself used (single-threaded), so it is robust against other processes.
double thread_cpu_ms();

/// OpenCV's own thread pool on one thread for the lifetime of the object (timed figures are
/// single-threaded), restored afterwards. Not thread-safe: cv::setNumThreads is process-wide, so
/// use it from the one thread that times.
class OneOpenCvThread {
 public:
  OneOpenCvThread();
  ~OneOpenCvThread();
  OneOpenCvThread(const OneOpenCvThread&) = delete;
  OneOpenCvThread& operator=(const OneOpenCvThread&) = delete;

 private:
  int before_;
};

/// Adds the wall and CPU time of `work()` to `t`; returns what work() returned.
template <class Work>
auto timed(PipelineTiming& t, Work&& work) {
  const double c0 = thread_cpu_ms();
  const Stopwatch clock;
  auto out = work();
  t.ms += clock.ms();
  t.cpu_ms += thread_cpu_ms() - c0;
  return out;
}

}  // namespace cropsight::pipeline
