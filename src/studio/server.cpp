// The studio server: opening the sequence or image folder, the lock, binding, and the helpers every handler uses
// (studio/server.hpp, server_state.hpp).
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/studio/access.hpp"
#include "studio/server_state.hpp"

namespace cropsight::studio {

namespace {

// A sequence or image folder the studio may write into: locked, and not opened --read-only.
std::unique_ptr<SequenceLock> try_lock(const std::filesystem::path& root, bool read_only) {
  if (read_only) return nullptr;
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) return nullptr;  // the reader says what is wrong
  if (::access(root.c_str(), W_OK) != 0) return nullptr;         // a read-only folder: a read-only studio
  return std::make_unique<SequenceLock>(root);
}

}  // namespace

ServerState::ServerState(StudioOptions o)
    : options(std::move(o)),
      lock(try_lock(root(), options.read_only)),
      writable(lock && lock->held()),
      reconciled(writable && !images_mode() && LabelStore::reconcile(options.sequence)) {
  if (options.token.empty()) options.token = new_token();
  if (images_mode()) {
    proposals = std::make_unique<ImageProposals>(options.model, options.detector);
    image_labels = std::make_unique<ImageLabelStore>(options.images, proposals->class_names(), !writable);
    return;
  }
  reader = std::make_unique<io::SequenceReader>(options.sequence);
  const auto& info = reader->info();
  labels = std::make_unique<LabelStore>(options.sequence, info.camera, info.frames, !writable);
  analyzer = std::make_unique<FrameAnalyzer>(*reader, options.model);
  training =
      std::make_unique<TrainingJob>(options.sequence, analyzer->config(), analyzer->model(), options.general_data);
  field_map = std::make_unique<FieldMapJob>(options.sequence, analyzer->model_name());
}

void reply_json(httplib::Response& res, const nlohmann::json& j, int status) {
  res.status = status;
  res.set_content(j.dump(), "application/json");
}

void reply_error(httplib::Response& res, int status, const std::string& message) {
  reply_json(res, {{"error", message}}, status);
}

std::optional<nlohmann::json> body_object(const httplib::Request& req, httplib::Response& res) {
  nlohmann::json j = nlohmann::json::parse(req.body, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    reply_error(res, 400, "the request body must be a JSON object");
    return std::nullopt;
  }
  return j;
}

std::optional<int> frame_of(const ServerState& s, const httplib::Request& req, httplib::Response& res) {
  const std::string digits = req.matches.size() > 1 ? std::string(req.matches[1]) : "";
  if (digits.empty() || digits.size() > 9 || std::stoi(digits) >= s.reader->size()) {
    reply_error(res, 404, "no frame " + digits);
    return std::nullopt;
  }
  return std::stoi(digits);
}

StudioServer::StudioServer(StudioOptions options) : s_(std::make_unique<ServerState>(std::move(options))) {
  auto& http = s_->http;
  http.set_payload_max_length(s_->options.max_body_bytes);
  // httplib's default also sets SO_REUSEPORT, with which a second studio of the same user binds a
  // port the first one serves and the kernel splits the connections between them: a taken port
  // must be an error instead.
  http.set_socket_options([](socket_t sock) {
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  http.set_default_headers(
      {{"Cache-Control", "no-store"},
       {"X-Content-Type-Options", "nosniff"},
       {"X-Frame-Options", "DENY"},
       {"Referrer-Policy", "no-referrer"},
       {"Content-Security-Policy", "default-src 'self'; img-src 'self' blob: data:; frame-ancestors 'none'"}});
  http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      reply_error(res, 500, e.what());
    }
  });
  add_access_checks(*s_);
  add_page_routes(*s_);
  if (s_->images_mode()) {
    add_image_routes(*s_);
  } else {
    add_frame_routes(*s_);
    add_training_routes(*s_);
    add_map_routes(*s_);
  }
  const std::string& bind = s_->options.bind;
  const std::string where = bind + ":" + std::to_string(s_->options.port);
  if (s_->options.port == 0)
    s_->port = http.bind_to_any_port(bind);
  else
    s_->port = http.bind_to_port(bind, s_->options.port) ? s_->options.port : -1;
  if (s_->port <= 0) throw Error(where, "cannot listen there (address in use or not this machine's)");
}

StudioServer::~StudioServer() {
  stop();
  if (s_->background.joinable()) s_->background.join();
}

void StudioServer::run() {
  {
    std::lock_guard lock(s_->run_mutex);
    if (s_->stopping) return;
    s_->run_started = true;
  }
  // Every frame's candidates (every image's boxes) once, in the background, so "least certain
  // first" covers the pass and the page need not wait for the detector.
  s_->background = std::thread([s = s_.get()] {
    const int count = s->images_mode() ? int(s->image_labels->images().size()) : s->reader->size();
    for (int f = 0; f < count && !s->stopping; ++f) {
      try {
        if (s->images_mode())
          s->proposals->detect(f, s->image_labels->image_path(f));
        else
          s->analyzer->analyse(f);
      } catch (const std::exception&) {
        // A frame that cannot be read is reported when the page asks for it.
      }
    }
  });
  s_->http.listen_after_bind();
  s_->run_finished = true;
}

void StudioServer::stop() {
  {
    std::lock_guard lock(s_->run_mutex);
    s_->stopping = true;
    if (!s_->run_started) return;
  }
  if (s_->training) s_->training->cancel();
  if (s_->field_map) s_->field_map->cancel();
  while (!s_->http.is_running() && !s_->run_finished) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  s_->http.stop();
}

int StudioServer::port() const { return s_->port; }
const std::string& StudioServer::token() const { return s_->options.token; }
bool StudioServer::writable() const { return s_->writable; }

std::string StudioServer::url() const {
  const std::string& b = s_->options.bind;
  const std::string host = (b == "0.0.0.0" || b == "::" || b == "127.0.0.1") ? "127.0.0.1" : b;
  return "http://" + host + ":" + std::to_string(s_->port) + "/?token=" + s_->options.token;
}

}  // namespace cropsight::studio
