// The studio's background training job (studio/training_job.hpp).
#include "cropsight/studio/training_job.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <functional>
#include <map>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/eval.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"
#include "studio/background_job.hpp"

namespace cropsight::studio {

namespace fs = std::filesystem;
namespace broccoli = pipeline::broccoli;

namespace {

// The labelled frames split into training and held-out frames: every fourth is held out, and at
// least one.
std::pair<std::vector<int>, std::vector<int>> split_held_out(const std::vector<int>& labelled) {
  std::vector<int> train, test;
  for (std::size_t k = 0; k < labelled.size(); ++k) (k % 4 == 3 ? test : train).push_back(labelled[k]);
  if (test.empty() && train.size() >= 2) {
    test.push_back(train.back());
    train.pop_back();
  }
  if (train.empty() || test.empty()) throw Error("training", "label two frames at least (one is held out)");
  return {train, test};
}

// Every labelled frame of `passes` (whole passes, as `train broccoli --extra-data` adds them).
void add_labelled_passes(const std::vector<fs::path>& passes, broccoli::DatasetBuilder& builder,
                         const std::function<void()>& step) {
  for (const auto& dir : passes) {
    const io::SequenceReader reader(dir);
    for (int f : reader.info().labelled_frames) {
      builder.add_frame(reader.read(f));
      step();
    }
  }
}

// The provenance's list of passes: comma separated, as --extra-data takes them.
std::string joined(const std::vector<fs::path>& paths) {
  std::string out;
  for (const auto& p : paths) out += (out.empty() ? "" : ",") + p.string();
  return out;
}

HeldOutFigures held_out_figures(const broccoli::Figures& f) {
  return {f.frames, f.clusters, f.truth_heads, f.confusion.kappa(), f.confusion.precision(), f.confusion.recall(),
          f.ap50};
}

}  // namespace

TrainingJob::TrainingJob(fs::path sequence, broccoli::Config config, std::shared_ptr<const learning::Model> current,
                         std::vector<fs::path> general)
    : sequence_(std::move(sequence)),
      config_(std::move(config)),
      current_(std::move(current)),
      general_(std::move(general)) {
  config_.track = false;
  for (const auto& dir : general_) {
    const io::SequenceReader reader(dir);  // names the file when it is no sequence
    if (io::resolved_path(dir) == io::resolved_path(sequence_))
      throw Error(dir.string(), "is the studio's own sequence; the general passes are other, labelled passes");
    if (reader.info().labelled_frames.empty())
      throw Error(dir.string(), "has no labels/ (simulate the general model's passes with their labels)");
    general_frames_ += long(reader.info().labelled_frames.size());
  }
}

TrainingJob::~TrainingJob() {
  cancel();
  if (thread_.joinable()) thread_.join();
}

bool TrainingJob::start(std::vector<int> labelled, bool with_general) {
  std::lock_guard lock(mutex_);
  if (status_.state == "running") return false;
  if (thread_.joinable()) thread_.join();  // the previous job has ended (its state says so)
  cancel_ = false;
  trained_.reset();
  status_ = TrainingStatus{};
  status_.state = "running";
  status_.with_general = with_general && !general_.empty();
  status_.general_frames = status_.with_general ? general_frames_ : 0;
  thread_ = std::thread([this, labelled = std::move(labelled), with = status_.with_general]() mutable {
    run(std::move(labelled), with);
  });
  return true;
}

void TrainingJob::cancel() { cancel_ = true; }

TrainingStatus TrainingJob::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

// One job: split, read and cluster the training frames (and the general passes'), train, score
// both models on the held-out frames.
void TrainingJob::run(std::vector<int> labelled, bool with_general) {
  run_job(mutex_, status_, [&] {
    // Named vectors, not a structured binding: Clang 14 (the fuzz build) cannot capture one in the
    // scoring lambda below.
    const auto split = split_held_out(labelled);
    const std::vector<int>& train = split.first;
    const std::vector<int>& test = split.second;
    const double steps = double(train.size() + 2 * test.size()) + (with_general ? double(general_frames_) : 0.0);
    double done = 0;
    auto step = [&] {
      if (cancel_) throw JobCancelled{};
      std::lock_guard lock(mutex_);
      status_.progress = ++done / steps;
    };
    {
      std::lock_guard lock(mutex_);
      status_.train_frames = train;
      status_.test_frames = test;
    }
    const io::SequenceReader reader(sequence_);
    broccoli::DatasetBuilder builder(config_.detector, config_.truth);
    for (int f : train) {
      builder.add_frame(reader.read(f));
      step();
    }
    std::map<std::string, std::string> provenance{{"data", sequence_.string()}, {"trained_by", "cropsight studio"}};
    if (with_general) {
      add_labelled_passes(general_, builder, step);
      provenance["extra_data"] = joined(general_);
    }
    provenance["frames"] = std::to_string(builder.frames());
    const auto& data = builder.dataset();
    if (data.positives() == 0 || data.negatives() == 0)
      throw Error("training", "the training frames' clusters are all of one class (" +
                                  std::to_string(data.positives()) + " heads); label frames with heads and without");
    auto model = std::make_shared<const learning::Model>(
        broccoli::train_model(data, config_.detector, config_.truth, provenance));
    auto score = [&](std::shared_ptr<const learning::Model> m) {
      broccoli::Pipeline pipe(config_, std::move(m));
      broccoli::Evaluator evaluator(pipe);
      for (int f : test) {
        evaluator.add_frame(reader.read(f));
        step();
      }
      return held_out_figures(evaluator.figures());
    };
    const HeldOutFigures trained = score(model), current = score(current_);
    std::lock_guard lock(mutex_);
    trained_ = model;
    status_.samples = long(data.size());
    status_.positives = long(data.positives());
    status_.trained = trained;
    status_.current = current;
    status_.state = "done";
  });
}

fs::path TrainingJob::keep(const fs::path& folder) {
  std::lock_guard lock(mutex_);
  if (!trained_ || status_.state != "done") throw Error("keep", "no finished model to keep");
  const fs::path dir = folder.empty() ? io::resolved_path(sequence_).parent_path() : folder;
  const std::string stem = "studio-" + io::resolved_path(sequence_).filename().string() + "-";
  // Written whole under a temporary name, then linked to the first free name: link() fails when
  // the name exists, so no file is ever replaced, even one that appears meanwhile.
  const fs::path tmp = io::temporary_sibling(dir / (stem + "model.json"));
  io::check_output_file(tmp, {"studio", false, {sequence_}});
  learning::save_model(tmp, *trained_);
  for (int n = 1; n < 100000; ++n) {
    const fs::path file = dir / (stem + std::to_string(n) + ".json");
    if (::link(tmp.c_str(), file.c_str()) == 0) {
      fs::remove(tmp);
      status_.state = "kept";
      status_.message = file.string();
      trained_.reset();
      return file;
    }
    if (errno != EEXIST) break;
  }
  const std::string why = std::strerror(errno);
  fs::remove(tmp);
  throw Error(dir.string(), "cannot write the model: " + why);
}

void TrainingJob::discard() {
  std::lock_guard lock(mutex_);
  if (!trained_ || status_.state != "done") throw Error("discard", "no finished model to discard");
  trained_.reset();
  status_.state = "discarded";
}

}  // namespace cropsight::studio
