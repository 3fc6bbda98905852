// Long runs (item 5): a pipeline fed many frames in one process, repeated from a short
// sequence held in memory, while resident memory is sampled (/proc/self/statm). It reports memory
// growth after warm-up, errors, and whether the outputs equal what they must:
//
//   long_run broccoli --data SEQ --model MODEL.json [--frames 10000] [--warmup 500] [--short 200]
//     detect, size and track (pipeline::broccoli::Pipeline, tracking on, the model's config as `detect
//     broccoli --track` runs it) over ONE pass of --frames frames: the sequence repeated, frames
//     renumbered, so the filter sees a field --frames long and its map grows with it. Checks:
//     the first --short frames' results (detections with sizes and track ids, predicted heads,
//     camera estimate) equal a fresh pipeline's on those frames alone; every frame's detections
//     (step 1 carries no state) equal those of its source frame.
//   ... --pass-frames N: passes of N frames instead (finish() and reset() between them, as a
//     robot at the end of each row); every pass sees the same frames, so every pass's results
//     must equal the short run's, and the pass state no longer grows with --frames.
//   long_run potato --data SEQ [--config potato] [--frames 10000] [--warmup 500]
//     the harvest loop (pipeline::potato::Pipeline) over the sequence, an approach, repeated with reset()
//     between approaches as a robot starts a new one: every approach's harvest messages must
//     equal the first's (target ids, which count up over the pipeline's life, in order of first
//     appearance within the approach).
//
// Prints progress lines with the resident memory to stderr and one JSON object to stdout. Exit 0
// when there was no error and every output check held, 1 otherwise, 2 on bad input. A developer
// tool, not a ctest (minutes of run time); the figures and commands are in docs/reliability.md.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"

using namespace cropsight;

namespace {

struct Options {
  std::string mode, data, model, config = "potato";
  int frames = 10000, warmup = 500, short_frames = 200, pass_frames = 0;
};

double resident_mib() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return double(resident) * double(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// FNV-1a over the bytes of the values a check compares: equal outputs give equal hashes, and a
// hash per frame keeps 10,000 frames' outputs in 80 kB.
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  template <class T>
  Hash& add(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    for (std::size_t i = 0; i < sizeof(T); ++i) h = (h ^ p[i]) * 1099511628211ull;
    return *this;
  }
  template <class T>
  Hash& add_all(const std::vector<T>& v) {
    add(v.size());
    for (const T& x : v) add(x);
    return *this;
  }
  Hash& add(const Eigen::Vector3f& v) { return add(v.x()).add(v.y()).add(v.z()); }
  Hash& add(const Eigen::Vector3d& v) { return add(v.x()).add(v.y()).add(v.z()); }
};

// Step 1's output (what the detector found), without what tracking adds to it.
std::uint64_t detections_hash(const std::vector<Detection>& dets) {
  Hash h;
  h.add(dets.size());
  for (const Detection& d : dets) h.add(d.score).add(d.centroid).add(d.box).add_all(d.indices);
  return h.h;
}

// Everything process() returns online, timings aside.
std::uint64_t broccoli_result_hash(const pipeline::broccoli::FrameResult& r) {
  Hash h;
  h.add(detections_hash(r.detections));
  for (const Detection& d : r.detections) h.add(d.size_m).add(d.track_id);
  h.add(r.predicted.size());
  for (const auto& p : r.predicted) h.add(p.track_id).add_all(p.indices).add(p.centroid).add(p.confirmed_online);
  h.add(r.association.camera_position).add(r.association.camera_velocity).add_all(r.association.track_ids);
  return h.h;
}

bool broccoli_result_finite(const pipeline::broccoli::FrameResult& r) {
  for (const Detection& d : r.detections)
    if (!std::isfinite(d.score) || !d.centroid.allFinite() || !std::isfinite(d.size_m)) return false;
  return r.association.camera_position.allFinite();
}

// Target ids count up over the pipeline's life (TargetTracker: 1, 2, ... per selected target; a
// reset keeps counting, so ids never repeat). Within an approach they are compared in order of
// first appearance: `ids` maps them to 1, 2, ... and is cleared at each approach.
std::uint64_t harvest_hash(const pipeline::potato::FrameResult& r, std::map<int, int>& ids) {
  auto t = r.target;
  if (t.target_id != 0) t.target_id = ids.emplace(t.target_id, int(ids.size()) + 1).first->second;
  Hash h;
  h.add(r.detections.size());
  for (const auto& d : r.detections) h.add(d);
  h.add(t.frame).add(t.timestamp).add(t.detection).add(t.depth_ok).add(t.x).add(t.y).add(t.z);
  h.add(t.height).add(t.width).add(t.angle).add(t.angle_ok).add(t.cut).add(t.target_id).add(t.state).add(t.score);
  h.add(t.box);
  return h.h;
}

std::vector<RgbdFrame> load_frames(const std::string& dir) {
  const io::SequenceReader reader(dir);
  std::vector<RgbdFrame> frames;
  for (int i = 0; i < reader.size(); ++i) {
    frames.push_back(reader.read(i));
    frames.back().labels = {};  // the pipelines never read ground truth
  }
  return frames;
}

// Memory samples: before the first frame, at warm-up, every 1000 frames, at the end.
struct Memory {
  double before = 0, warm = 0, end = 0, peak = 0;
  nlohmann::json samples = nlohmann::json::array();
  void sample(int done, int total, int warmup, nlohmann::json s = nlohmann::json::object()) {
    const double mib = resident_mib();
    peak = std::max(peak, mib);
    if (done == warmup) warm = mib;
    if (done == total) end = mib;
    s["frame"] = done;
    s["rss_mib"] = mib;
    std::fprintf(stderr, "long_run: %s\n", s.dump().c_str());
    samples.push_back(std::move(s));
  }
  bool due(int done, int total, int warmup) const { return done == warmup || done == total || done % 1000 == 0; }
  nlohmann::json json() const {
    return {{"rss_before_mib", before},
            {"rss_warm_mib", warm},
            {"rss_end_mib", end},
            {"rss_peak_mib", peak},
            {"growth_after_warmup_pct", warm > 0 ? 100.0 * (end - warm) / warm : 0.0},
            {"samples", samples}};
  }
};

// Long on purpose: the short reference run, the long run with its memory samples, and the summary of one soak test.
nlohmann::json run_broccoli(const Options& o) {
  // Built the way every front-end builds it; twice, so that the long run starts from a fresh state.
  const pipeline::PipelineSpec spec{.sets = {"track=true"}, .model = o.model};
  const std::vector<RgbdFrame> source = load_frames(o.data);
  const int n = int(source.size());
  // Renumbered repeats: frame i is source frame i % n, its index i, its time and camera position
  // moved on by whole sequence lengths (as if the tractor drove on over an identical field).
  const double period_s = n > 1 ? (source[n - 1].timestamp - source[0].timestamp) * n / (n - 1) : 0.0;
  Eigen::Vector3d period_m = Eigen::Vector3d::Zero();
  if (n > 1 && source[0].camera_position && source[n - 1].camera_position)
    period_m = (*source[n - 1].camera_position - *source[0].camera_position) * double(n) / double(n - 1);
  auto frame_at = [&](int i, RgbdFrame& f) {
    const RgbdFrame& s = source[std::size_t(i % n)];
    f.index = i;
    f.timestamp = s.timestamp + period_s * (i / n);
    if (s.camera_position) f.camera_position = *s.camera_position + period_m * double(i / n);
  };

  // The short run and the source frames' detections, first, in a pipeline of their own.
  const int short_frames = std::min(o.short_frames, o.frames);
  std::vector<std::uint64_t> short_hash(static_cast<std::size_t>(short_frames)),
      source_dets(static_cast<std::size_t>(n));
  {
    const auto built = pipeline::broccoli::make_pipeline(spec);
    pipeline::broccoli::Pipeline& pipe = *built;
    RgbdFrame f = source[0];
    for (int i = 0; i < short_frames; ++i) {
      f = source[std::size_t(i % n)];
      frame_at(i, f);
      const auto& r = pipe.process(f);
      short_hash[std::size_t(i)] = broccoli_result_hash(r);
      if (i < n) source_dets[std::size_t(i)] = detections_hash(r.detections);
    }
    for (int i = short_frames; i < n; ++i)
      source_dets[std::size_t(i)] = detections_hash(pipe.process(source[i]).detections);
  }

  const auto built = pipeline::broccoli::make_pipeline(spec);
  pipeline::broccoli::Pipeline& pipe = *built;
  Memory mem;
  mem.before = resident_mib();
  int errors = 0, nonfinite = 0, short_mismatch = 0, detection_mismatch = 0, passes = 1;
  long detections = 0, map_heads = 0;
  std::string first_error;
  RgbdFrame f;
  for (int i = 0; i < o.frames; ++i) {
    const int j = o.pass_frames > 0 ? i % o.pass_frames : i;  // frame of the current pass
    if (o.pass_frames > 0 && i > 0 && j == 0) {
      map_heads += long(pipe.finish().size());
      pipe.reset();
      ++passes;
    }
    f = source[std::size_t(j % n)];  // copy-assign into the same buffers: no allocation per frame
    frame_at(j, f);
    try {
      const auto& r = pipe.process(f);
      detections += long(r.detections.size());
      if (!broccoli_result_finite(r)) ++nonfinite;
      if (j < short_frames && broccoli_result_hash(r) != short_hash[std::size_t(j)]) ++short_mismatch;
      if (detections_hash(r.detections) != source_dets[std::size_t(j % n)]) ++detection_mismatch;
    } catch (const std::exception& e) {
      if (errors++ == 0) first_error = e.what();
    }
    // The pass's state that grows with it: heads tracked (T) and mapped (M), and the detections
    // the mapper records for the pass's offline scores.
    if (mem.due(i + 1, o.frames, o.warmup)) {
      const auto& m = pipe.mapper();
      mem.sample(i + 1, o.frames, o.warmup,
                 {{"tracked", m.filter().tracked().size()},
                  {"mapped", m.filter().mapped().size()},
                  {"recorded_detections", m.detections().size()}});
    }
  }
  map_heads += long(pipe.finish().size());
  const double rss_after_finish = resident_mib();
  return {{"pipeline", "broccoli"},
          {"data", o.data},
          {"model", o.model},
          {"source_frames", n},
          {"frames", o.frames},
          {"warmup", o.warmup},
          {"pass_frames", o.pass_frames},
          {"passes", passes},
          {"detections", detections},
          {"map_heads", map_heads},
          {"errors", errors},
          {"first_error", first_error},
          {"nonfinite_frames", nonfinite},
          {"short_run_frames", short_frames},
          {"short_run_mismatches", short_mismatch},
          {"detection_mismatches", detection_mismatch},
          {"rss_after_finish_mib", rss_after_finish},
          {"memory", mem.json()},
          {"ok", errors == 0 && nonfinite == 0 && short_mismatch == 0 && detection_mismatch == 0}};
}

nlohmann::json run_potato(const Options& o) {
  namespace pp = pipeline::potato;
  const pipeline::PipelineSpec spec{.preset = o.config};
  const std::vector<RgbdFrame> source = load_frames(o.data);
  const int n = int(source.size());
  std::vector<std::uint64_t> first(static_cast<std::size_t>(n));
  std::map<int, int> ids;
  {
    const auto built = pp::make_pipeline(spec);
    pp::Pipeline& pipe = *built;
    for (int i = 0; i < n; ++i) first[std::size_t(i)] = harvest_hash(pipe.process(source[std::size_t(i)]), ids);
  }
  const auto built = pp::make_pipeline(spec);
  pp::Pipeline& pipe = *built;
  Memory mem;
  mem.before = resident_mib();
  int errors = 0, nonfinite = 0, mismatch = 0, with_target = 0;
  std::string first_error;
  for (int i = 0; i < o.frames; ++i) {
    if (i % n == 0) {  // a new approach
      pipe.reset();
      ids.clear();
    }
    try {
      const pp::FrameResult r = pipe.process(source[std::size_t(i % n)]);
      with_target += r.target.detection ? 1 : 0;
      if (!std::isfinite(r.target.x) || !std::isfinite(r.target.y) || !std::isfinite(r.target.z) ||
          !std::isfinite(r.target.angle))
        ++nonfinite;
      if (harvest_hash(r, ids) != first[std::size_t(i % n)]) ++mismatch;
    } catch (const std::exception& e) {
      if (errors++ == 0) first_error = e.what();
    }
    if (mem.due(i + 1, o.frames, o.warmup)) mem.sample(i + 1, o.frames, o.warmup);
  }
  return {{"pipeline", "potato"},
          {"data", o.data},
          {"config", o.config},
          {"source_frames", n},
          {"approaches", (o.frames + n - 1) / n},
          {"frames", o.frames},
          {"warmup", o.warmup},
          {"frames_with_target", with_target},
          {"errors", errors},
          {"first_error", first_error},
          {"nonfinite_frames", nonfinite},
          {"approach_mismatches", mismatch},
          {"memory", mem.json()},
          {"ok", errors == 0 && nonfinite == 0 && mismatch == 0}};
}

[[noreturn]] void usage() {
  std::fprintf(stderr,
               "usage: long_run broccoli --data SEQ --model MODEL.json [--frames N] [--warmup N] [--short N] "
               "[--pass-frames N]\n"
               "       long_run potato --data SEQ [--config PRESET] [--frames N] [--warmup N]\n");
  std::exit(2);
}

Options parse(int argc, char** argv) {
  if (argc < 2) usage();
  Options o;
  o.mode = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string key = argv[i];
    if (i + 1 >= argc) usage();
    const std::string value = argv[++i];
    auto number = [&] {
      try {
        return std::stoi(value);
      } catch (const std::exception&) {
        throw Error(key, "'" + value + "' is not a whole number");
      }
    };
    if (key == "--data")
      o.data = value;
    else if (key == "--model")
      o.model = value;
    else if (key == "--config")
      o.config = value;
    else if (key == "--frames")
      o.frames = number();
    else if (key == "--warmup")
      o.warmup = number();
    else if (key == "--short")
      o.short_frames = number();
    else if (key == "--pass-frames")
      o.pass_frames = number();
    else
      usage();
  }
  if (o.data.empty() || (o.mode == "broccoli" && o.model.empty())) usage();
  if (o.frames < 1 || o.warmup < 1 || o.warmup > o.frames) throw Error("--warmup", "must be in [1, --frames]");
  if (o.short_frames < 0 || o.pass_frames < 0) throw Error("--short/--pass-frames", "must not be negative");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    nlohmann::json j;
    if (o.mode == "broccoli")
      j = run_broccoli(o);
    else if (o.mode == "potato")
      j = run_potato(o);
    else
      usage();
    std::printf("%s\n", j.dump(1).c_str());
    return j["ok"].get<bool>() ? 0 : 1;
  } catch (const Error& e) {
    std::fprintf(stderr, "long_run: %s\n", e.what());
    return 2;
  }
}
