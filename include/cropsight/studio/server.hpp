#pragma once
// The studio's HTTP server (cpp-httplib, Debian's libcpp-httplib-dev): the page (its files are
// compiled into the library, so nothing is read from disk to serve it), the frames of one depth
// sequence as pictures, the model's candidates, the labels, and the training job; or, for a
// folder of images (StudioOptions::images), the images, the potato detector's boxes and the
// boxes and polygons a user draws (image_label_store.hpp says where they are written).
//
// Every request passes the checks of access.hpp (Host, then token) before any handler; request
// bodies are bounded (413 above StudioOptions::max_body_bytes); a body that is not the JSON a
// handler expects is 400; sequence files are served only through sequence_files.hpp. A writer
// holds the sequence's lock (sequence_lock.hpp); without it the studio is read-only and every
// writing request is 403.
//
// Endpoints (JSON unless noted; frame numbers from 0):
//   GET  /, /studio.js, /studio.css             the page
//   GET  /api/info                              frames, size, model, threshold, labelled, read_only
//   GET  /api/frame/N/depth.png | color.png     the depth colour map (near red, far blue) | colour
//   GET  /api/frame/N/candidates                {threshold, certainty, candidates: [{score, head, runs}]}
//   GET  /api/frame/N/labels                    {labelled, heads: [runs...]}
//   POST /api/frame/N/labels                    {heads: [runs...]}: writes the frame's labels
//   GET  /api/uncertain                         frames analysed so far, least certain first
//   POST /api/train {with_general?} | /api/train/cancel | /api/train/keep | /api/train/discard
//   GET  /api/train                             the job's TrainingStatus
//   POST /api/map | /api/map/cancel             builds the field map in the background (field_map_job.hpp)
//   GET  /api/map                               {state, progress, poses, heads: [{id, x, y, diameter_mm, frames...}],
//   camera} GET  /files/PATH                            a file of the sequence (sequence_files.hpp)
// "runs" are pixel runs [start, length, start, length, ...] over row-major pixel indices.
//
// With a folder of images, in place of the frame and training endpoints:
//   GET  /, /images.js                          the image page (images.html)
//   GET  /api/info                              images (names), classes, model, labelled, read_only
//   GET  /api/image/N/pixels                    the image file as it is
//   GET  /api/image/N/proposals                 the detector's {shapes: [{label, score, box}]}
//   GET  /api/image/N/labels                    {name, width, height, labelled, shapes}
//   POST /api/image/N/labels                    {shapes: [{label, box | polygon}]} (image_shapes.hpp)
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace cropsight::studio {

struct StudioOptions {
  std::filesystem::path sequence;         ///< a depth sequence folder (docs/formats.md)
  std::filesystem::path images;           ///< or a folder of images (then `sequence` is unused)
  std::string model;                      ///< broccoli model, or for images an ONNX detector ("" = default)
  std::string detector;                   ///< images: the project's 2D detector instead (image_proposals.hpp)
  std::string bind = "127.0.0.1";         ///< address to listen on
  int port = 0;                           ///< 0 = a free port chosen by the kernel
  bool read_only = false;                 ///< never write, even when the lock is free
  std::size_t max_body_bytes = 8u << 20;  ///< larger request bodies are refused (413)
  std::string token;                      ///< "" = a new random token (access.hpp)
  /// Where "keep" writes a model trained on the page ("" = the sequence's parent folder). Named
  /// here, never by a request, so no page can make the studio write elsewhere.
  std::filesystem::path models_dir;
  /// Labelled passes a training job may add when the page asks (the general model's training
  /// passes, simulated by the user: docs/studio.md); empty = training on the sequence only.
  std::vector<std::filesystem::path> general_data;
};

struct ServerState;  // studio/server_state.hpp (internal)

class StudioServer {
 public:
  /// Opens the sequence and the model, takes the lock unless read-only, and binds the port.
  /// Throws Error naming the sequence, the model or the address when any of it fails.
  explicit StudioServer(StudioOptions options);
  ~StudioServer();
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  /// Serves until stop() (from another thread or a signal watcher). The port is bound by the
  /// constructor, so clients may connect before run() starts (they wait in the backlog).
  void run();
  void stop();

  int port() const;
  const std::string& token() const;
  /// Whether this studio writes labels (false: --read-only, or another studio holds the lock).
  bool writable() const;
  /// The address to open: http://HOST:PORT/?token=TOKEN.
  std::string url() const;

 private:
  std::unique_ptr<ServerState> s_;
};

}  // namespace cropsight::studio
