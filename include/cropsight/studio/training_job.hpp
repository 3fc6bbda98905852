#pragma once
// Training from the studio page: one background thread trains a broccoli classifier on the
// labelled frames of the sequence (with the configuration the studio's model runs with, as
// `train broccoli` would from the same labels), then scores the new model and the studio's model
// on labelled frames the training did not see (the broccoli Evaluator: per-cluster κ, precision,
// recall and AP50). The page polls status(), may cancel(), and then keeps or discards the model.
//
// Held out: every fourth labelled frame (the 4th, 8th, ...), and at least one, so the figures are
// never on training frames; two labelled frames at least, with heads and other clusters among the
// training frames' clusters.
//
// With the general model's training passes (StudioOptions::general_data, the user's simulated
// copies of the passes models/README.md lists), a job may add every labelled frame of those passes
// to the sequence's training frames, as `train broccoli --extra-data` does; the held-out frames stay
// the sequence's own. The model file's provenance lists the passes (key extra_data).
//
// Thread-safe: every public call may come from any server thread.
#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"

namespace cropsight::studio {

/// A model's figures on the held-out frames (per cluster, Table I of Montes et al.; AP50 over
/// every labelled head).
struct HeldOutFigures {
  long frames = 0, clusters = 0, heads = 0;
  double kappa = 0.0, precision = 0.0, recall = 0.0, ap50 = 0.0;
};

struct TrainingStatus {
  std::string state = "idle";  ///< idle | running | done | failed | cancelled | kept | discarded
  double progress = 0.0;       ///< 0..1 of the frames to read and score
  std::string message;         ///< the error of a failed job; the file of a kept model
  std::vector<int> train_frames, test_frames;
  long samples = 0, positives = 0;
  double seconds = 0.0;
  bool with_general = false;        ///< the job trains on the general passes too
  long general_frames = 0;          ///< frames of the general passes trained on
  HeldOutFigures trained, current;  ///< the new model and the studio's model on test_frames
};

class TrainingJob {
 public:
  /// `sequence`: the sequence folder (its labels are read when a job starts); `config` and
  /// `current`: the studio's pipeline configuration and model; `general`: labelled passes a job may
  /// add (the general model's training set). Throws Error naming a general pass that is no
  /// labelled sequence, or that is the studio's sequence itself.
  TrainingJob(std::filesystem::path sequence, pipeline::broccoli::Config config,
              std::shared_ptr<const learning::Model> current, std::vector<std::filesystem::path> general = {});
  /// Cancels a running job and waits for it.
  ~TrainingJob();
  TrainingJob(const TrainingJob&) = delete;
  TrainingJob& operator=(const TrainingJob&) = delete;

  /// Starts a job on `labelled` (ascending frame numbers), with every labelled frame of the
  /// general passes too when `with_general`; false when one is running.
  bool start(std::vector<int> labelled, bool with_general = false);
  /// The general passes and their labelled frames (0 and 0 without).
  std::size_t general_passes() const { return general_.size(); }
  long general_frames() const { return general_frames_; }
  void cancel();
  TrainingStatus status() const;
  /// Writes the finished model into `folder` (the sequence's parent when empty) under a new name
  /// ("studio-SEQ-N.json", N the first number free), atomically and never over an existing file.
  /// Returns the file. Throws Error when there is no finished model or the folder is not writable.
  std::filesystem::path keep(const std::filesystem::path& folder);
  /// Drops the finished model. Throws Error when there is none.
  void discard();

 private:
  void run(std::vector<int> labelled, bool with_general);

  std::filesystem::path sequence_;
  pipeline::broccoli::Config config_;
  std::shared_ptr<const learning::Model> current_;
  std::vector<std::filesystem::path> general_;
  long general_frames_ = 0;
  mutable std::mutex mutex_;
  TrainingStatus status_;
  std::shared_ptr<const learning::Model> trained_;
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

}  // namespace cropsight::studio
