#pragma once
// Per-stage wall-clock timing. Not thread-safe: one StageTimer per thread / pipeline instance.
#include <chrono>
#include <string>
#include <vector>

namespace cropsight {

/// Wall-clock time since construction (or restart()): the one way to time a span of code that is
/// not a named stage (a whole command, a training run).
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  void restart() { start_ = std::chrono::steady_clock::now(); }
  double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }
  double seconds() const { return ms() / 1000.0; }

 private:
  std::chrono::steady_clock::time_point start_;
};

class StageTimer {
 public:
  struct Stage {
    std::string name;
    double total_ms = 0.0;
    long count = 0;
    double mean_ms() const { return count ? total_ms / double(count) : 0.0; }
  };

  /// RAII scope: adds its lifetime to stage `name`.
  class Scope {
   public:
    Scope(StageTimer& t, std::string name)
        : timer_(t), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}
    ~Scope() {
      timer_.add(name_, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count());
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StageTimer& timer_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
  };

  Scope scope(std::string name) { return Scope(*this, std::move(name)); }
  void add(const std::string& name, double ms);
  const std::vector<Stage>& stages() const { return stages_; }  ///< in first-seen order
  double total_ms() const;
  /// Total of stage `name`, ms; 0 when it never ran.
  double ms(const std::string& name) const;
  /// What ran since `earlier` (a copy of stages() taken then): each stage's added time and count,
  /// stages that did not run left out. A pipeline whose steps keep one cumulative timer gives each
  /// frame its own stages this way.
  StageTimer since(const std::vector<Stage>& earlier) const;
  void clear() { stages_.clear(); }

 private:
  std::vector<Stage> stages_;
};

/// One stage's mean time per frame, ms.
struct StageMs {
  std::string name;
  double ms = 0.0;
};

/// Each stage's total over `frames` (0 when there are none), in stage order. A stage that ran on
/// some frames only is averaged over all of them, so that the stages add up to the time per frame
/// (Stage::mean_ms is per run of the stage).
std::vector<StageMs> per_frame_ms(const std::vector<StageTimer::Stage>& stages, long frames);

}  // namespace cropsight
