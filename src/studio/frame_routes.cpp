// Frames, the model's candidates and the labels (server_state.hpp).
#include <algorithm>
#include <cmath>

#include "cropsight/io/image_io.hpp"
#include "cropsight/report/render.hpp"
#include "studio/pixel_runs.hpp"
#include "studio/server_state.hpp"

namespace cropsight::studio {

namespace {

nlohmann::json info_json(const ServerState& s) {
  const auto& info = s.reader->info();
  return {{"sequence", s.options.sequence.filename().string()},
          {"frames", info.frames},
          {"width", info.camera.width},
          {"height", info.camera.height},
          {"has_color", info.has_color},
          {"model", s.analyzer->model_name()},
          {"threshold", s.analyzer->threshold()},
          {"labelled", s.labels->labelled()},
          {"read_only", !s.writable},
          {"general_passes", s.training->general_passes()},
          {"general_frames", s.training->general_frames()}};
}

nlohmann::json candidates_json(const FrameCandidates& fc, float threshold) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& c : fc.candidates)
    list.push_back({{"score", c.score}, {"head", c.head}, {"diameter_mm", c.diameter_mm}, {"runs", to_runs(c.pixels)}});
  return {{"frame", fc.frame},
          {"threshold", threshold},
          {"certainty", std::isfinite(fc.certainty) ? nlohmann::json(fc.certainty) : nlohmann::json(nullptr)},
          {"candidates", std::move(list)}};
}

// A label image as one run list per head id, ids ascending.
nlohmann::json heads_json(const LabelImage& labels) {
  std::map<int, std::vector<int>> heads;
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels.data[p] != 0) heads[labels.data[p]].push_back(int(p));
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [id, pixels] : heads) out.push_back(to_runs(pixels));
  return out;
}

// POST /api/frame/N/labels: {"heads": [runs, ...]}.
void save_labels(ServerState& s, int frame, const httplib::Request& req, httplib::Response& res) {
  if (!s.writable) return reply_error(res, 403, "this studio is read-only (--read-only, or another studio writes)");
  const auto& cam = s.reader->info().camera;
  std::string error;
  const auto heads = parse_heads_body(req.body, cam.width * cam.height, error);
  if (!heads) return reply_error(res, 400, error);
  s.labels->save(frame, *heads, s.reader->read(frame).depth);
  reply_json(res, {{"frame", frame}, {"heads", heads->size()}, {"labelled", s.labels->labelled()}});
}

}  // namespace

void add_frame_routes(ServerState& s) {
  auto& http = s.http;
  http.Get("/api/info", [&s](const httplib::Request&, httplib::Response& res) { reply_json(res, info_json(s)); });
  http.Get(R"(/api/frame/(\d+)/depth\.png)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto f = frame_of(s, req, res)) {
      const RgbdFrame frame = s.reader->read(*f);
      res.set_content(io::encode_png(report::depth_colormap(frame.depth, frame.camera.depth_scale)), "image/png");
    }
  });
  http.Get(R"(/api/frame/(\d+)/color\.png)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto f = frame_of(s, req, res)) {
      if (!s.reader->info().has_color) return reply_error(res, 404, "the sequence has no colour frames");
      res.set_content(io::encode_png(s.reader->read(*f).color), "image/png");
    }
  });
  http.Get(R"(/api/frame/(\d+)/candidates)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto f = frame_of(s, req, res))
      reply_json(res, candidates_json(*s.analyzer->analyse(*f), s.analyzer->threshold()));
  });
  http.Get(R"(/api/frame/(\d+)/labels)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto f = frame_of(s, req, res)) {
      const LabelImage labels = s.labels->labels(*f);
      reply_json(res, {{"frame", *f}, {"labelled", !labels.empty()}, {"heads", heads_json(labels)}});
    }
  });
  http.Post(R"(/api/frame/(\d+)/labels)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto f = frame_of(s, req, res)) save_labels(s, *f, req, res);
  });
  http.Get("/api/uncertain", [&s](const httplib::Request&, httplib::Response& res) {
    std::vector<std::pair<float, int>> order;
    for (int f = 0; f < s.reader->size(); ++f)
      if (const auto fc = s.analyzer->cached(f)) order.emplace_back(fc->certainty, f);
    std::stable_sort(order.begin(), order.end());
    nlohmann::json frames = nlohmann::json::array();
    for (const auto& [certainty, f] : order)
      frames.push_back({{"frame", f}, {"certainty", std::isfinite(certainty) ? nlohmann::json(certainty) : nullptr}});
    reply_json(res, {{"analysed", order.size()}, {"frames", s.reader->size()}, {"least_certain_first", frames}});
  });
}

}  // namespace cropsight::studio
