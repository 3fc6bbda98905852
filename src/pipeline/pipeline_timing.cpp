// Thread CPU clock, speed ratios and the one-OpenCV-thread guard for pipeline timing (see pipeline_timing.hpp).
#include "cropsight/pipeline/pipeline_timing.hpp"

#include <time.h>

#include <opencv2/core/utility.hpp>

namespace cropsight::pipeline {

double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

SpeedRatio time_ratio(const PipelineTiming& num, const PipelineTiming& den) {
  return {den.ms_per_frame() > 0 ? num.ms_per_frame() / den.ms_per_frame() : 0.0,
          den.cpu_ms_per_frame() > 0 ? num.cpu_ms_per_frame() / den.cpu_ms_per_frame() : 0.0};
}

OneOpenCvThread::OneOpenCvThread() : before_(cv::getNumThreads()) { cv::setNumThreads(1); }
OneOpenCvThread::~OneOpenCvThread() { cv::setNumThreads(before_); }

}  // namespace cropsight::pipeline
