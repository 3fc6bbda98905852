// The field map from the page: start, follow, cancel (server_state.hpp, studio/field_map_job.hpp).
#include "studio/server_state.hpp"

namespace cropsight::studio {

namespace {

nlohmann::json map_json(const FieldMapStatus& m) {
  nlohmann::json heads = nlohmann::json::array();
  for (const auto& [h, frames] : m.heads)
    heads.push_back({{"id", h.id},
                     {"x", h.position.x()},
                     {"y", h.position.y()},
                     {"z", h.position.z()},
                     {"diameter_mm", h.diameter_mm},
                     {"harvestable", h.harvestable},
                     {"frames_seen", h.frames_seen},
                     {"first_frame", h.first_frame},
                     {"last_frame", h.last_frame},
                     {"frames", frames}});
  nlohmann::json camera = nlohmann::json::array();
  for (const auto& c : m.camera) camera.push_back({c.x(), c.y(), c.z()});
  return {{"state", m.state},     {"progress", m.progress},    {"message", m.message},       {"poses", m.poses},
          {"seconds", m.seconds}, {"heads", std::move(heads)}, {"camera", std::move(camera)}};
}

}  // namespace

void add_map_routes(ServerState& s) {
  s.http.Get("/api/map", [&s](const httplib::Request&, httplib::Response& res) {
    reply_json(res, map_json(s.field_map->status()));
  });
  s.http.Post("/api/map", [&s](const httplib::Request& req, httplib::Response& res) {
    if (!body_object(req, res)) return;
    if (!s.field_map->start()) return reply_error(res, 409, "the field map is being built");
    reply_json(res, map_json(s.field_map->status()), 202);
  });
  s.http.Post("/api/map/cancel", [&s](const httplib::Request&, httplib::Response& res) {
    s.field_map->cancel();
    reply_json(res, map_json(s.field_map->status()));
  });
}

}  // namespace cropsight::studio
