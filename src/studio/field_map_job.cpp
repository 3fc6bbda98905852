// The studio's field map job (studio/field_map_job.hpp).
#include "cropsight/studio/field_map_job.hpp"

#include <map>
#include <set>

#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "studio/background_job.hpp"

namespace cropsight::studio {

namespace fs = std::filesystem;

namespace {

// The map's id of a track: the filter merges a head lost and found again into the earlier one
// (merged_ids: from → into), so a frame's detection may carry an id the map no longer has. The
// kept id is always a group's first track, never itself merged (as HeadMapper::finish relies on).
int map_id(int id, const std::vector<std::pair<int, int>>& merged) {
  for (const auto& [from, into] : merged)
    if (from == id) return into;
  return id;
}

}  // namespace

FieldMapJob::FieldMapJob(fs::path sequence, std::string model)
    : sequence_(std::move(sequence)), model_(std::move(model)) {}

FieldMapJob::~FieldMapJob() {
  cancel();
  if (thread_.joinable()) thread_.join();
}

bool FieldMapJob::start() {
  std::lock_guard lock(mutex_);
  if (status_.state == "running") return false;
  if (thread_.joinable()) thread_.join();  // the previous job has ended (its state says so)
  cancel_ = false;
  status_ = FieldMapStatus{};
  status_.state = "running";
  thread_ = std::thread([this] { run(); });
  return true;
}

void FieldMapJob::cancel() { cancel_ = true; }

FieldMapStatus FieldMapJob::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

// One pass in frame order, as `detect broccoli --track` runs it; then the map and each head's frames.
void FieldMapJob::run() {
  run_job(mutex_, status_, [&] {
    auto pipe = pipeline::broccoli::make_pipeline(
        {.sets = {"track=true"}, .model = model_.empty() ? pipeline::broccoli::kDefaultModel : model_});
    const io::SequenceReader reader(sequence_);
    const bool poses = reader.info().has_poses;
    std::map<int, std::set<int>> frames_of;  // track id → frames
    std::vector<Eigen::Vector3d> camera;
    for (int f = 0; f < reader.size(); ++f) {
      if (cancel_) throw JobCancelled{};
      RgbdFrame frame = reader.read(f);
      frame.labels = {};  // the model's view only, as the candidates
      const auto r = pipe->process(frame);
      for (const auto& d : r.detections)
        if (d.track_id >= 0) frames_of[d.track_id].insert(f);
      camera.push_back(r.association.camera_position);
      std::lock_guard lock(mutex_);
      status_.progress = double(f + 1) / reader.size();
    }
    const auto& map = pipe->finish();
    const auto& merged = pipe->mapper().filter().merged_ids();
    std::map<int, std::set<int>> frames_of_head;
    for (const auto& [id, frames] : frames_of) frames_of_head[map_id(id, merged)].insert(frames.begin(), frames.end());
    std::vector<MapHead> heads;
    for (const auto& h : map) {
      const auto& frames = frames_of_head[h.id];
      heads.push_back({h, std::vector<int>(frames.begin(), frames.end())});
    }
    std::lock_guard lock(mutex_);
    status_.heads = std::move(heads);
    status_.camera = std::move(camera);
    status_.poses = poses;
    status_.state = "done";
  });
}

}  // namespace cropsight::studio
