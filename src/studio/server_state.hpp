#pragma once
// What the studio's request handlers share (internal to src/studio): the sequence, its lock and
// labels, the model's candidates, the training job and the HTTP server, plus the helpers every
// handler uses to answer.
#include "studio/http.hpp"

#include <atomic>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "cropsight/io/sequence.hpp"
#include "cropsight/studio/field_map_job.hpp"
#include "cropsight/studio/frame_candidates.hpp"
#include "cropsight/studio/image_label_store.hpp"
#include "cropsight/studio/image_proposals.hpp"
#include "cropsight/studio/label_store.hpp"
#include "cropsight/studio/sequence_lock.hpp"
#include "cropsight/studio/server.hpp"
#include "cropsight/studio/training_job.hpp"

namespace cropsight::studio {

struct ServerState {
  explicit ServerState(StudioOptions o);
  bool images_mode() const { return !options.images.empty(); }
  /// The folder the studio serves and writes into: the sequence or the image folder.
  const std::filesystem::path& root() const { return images_mode() ? options.images : options.sequence; }

  // In this order: the lock, then labelled.csv repaired, then the reader that checks it.
  StudioOptions options;
  std::unique_ptr<SequenceLock> lock;
  bool writable = false;
  bool reconciled = false;
  // A depth sequence (--data): these four, and the image members stay null.
  std::unique_ptr<io::SequenceReader> reader;  // read() is const and only reads files: shared by the handlers
  std::unique_ptr<LabelStore> labels;
  std::unique_ptr<FrameAnalyzer> analyzer;
  std::unique_ptr<TrainingJob> training;
  std::unique_ptr<FieldMapJob> field_map;
  // A folder of images (--images): these two, and the depth members stay null.
  std::unique_ptr<ImageLabelStore> image_labels;
  std::unique_ptr<ImageProposals> proposals;
  httplib::Server http;
  int port = 0;
  std::atomic<bool> stopping{false};
  // run() and stop() from two threads: stop() before run() must keep run() from listening, and
  // stop() during run() must wait until the server listens (httplib's stop() does nothing before).
  std::mutex run_mutex;
  bool run_started = false;
  std::atomic<bool> run_finished{false};
  std::thread background;  // analyses every frame once, for "least certain first"
};

/// Answers `j` with `status`.
void reply_json(httplib::Response& res, const nlohmann::json& j, int status = 200);
/// Answers {"error": message} with `status`.
void reply_error(httplib::Response& res, int status, const std::string& message);
/// The request body as a JSON object; answers 400 and returns nothing when it is not one.
std::optional<nlohmann::json> body_object(const httplib::Request& req, httplib::Response& res);
/// The frame number of the route's first group; answers 404 and returns nothing when it is not
/// a frame of the sequence.
std::optional<int> frame_of(const ServerState& s, const httplib::Request& req, httplib::Response& res);

/// The route groups (page_routes.cpp, frame_routes.cpp, training_routes.cpp, map_routes.cpp,
/// image_routes.cpp).
void add_page_routes(ServerState& s);
void add_frame_routes(ServerState& s);
void add_training_routes(ServerState& s);
void add_map_routes(ServerState& s);
void add_image_routes(ServerState& s);
/// Host and token checks before every handler (access.hpp).
void add_access_checks(ServerState& s);

}  // namespace cropsight::studio
