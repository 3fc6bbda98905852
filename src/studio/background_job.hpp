#pragma once
// How the studio's background jobs (training_job.hpp, field_map_job.hpp) end (internal to
// src/studio): the page polls a status that says whether a job finished, was cancelled or failed
// and why, and how long it ran.
#include <chrono>
#include <exception>
#include <mutex>

namespace cropsight::studio {

/// Thrown inside a job's work when the page cancelled it.
struct JobCancelled {};

/// Runs `work` on the job's thread. `work` stores its results and sets status.state = "done"
/// itself (under `mutex`); an exception ends it as "cancelled" (JobCancelled) or "failed" (with
/// the exception's message). status.seconds is then the time it ran.
template <class Status, class Work>
void run_job(std::mutex& mutex, Status& status, Work&& work) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    work();
  } catch (const JobCancelled&) {
    std::lock_guard lock(mutex);
    status.state = "cancelled";
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex);
    status.state = "failed";
    status.message = e.what();
  }
  std::lock_guard lock(mutex);
  status.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace cropsight::studio
