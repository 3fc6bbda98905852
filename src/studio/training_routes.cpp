// Training from the page: start, follow, cancel, keep or discard (server_state.hpp).
#include "studio/server_state.hpp"

namespace cropsight::studio {

namespace {

nlohmann::json figures_json(const HeldOutFigures& f) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"frames", f.frames},       {"clusters", f.clusters},           {"heads", f.heads},
          {"kappa", number(f.kappa)}, {"precision", number(f.precision)}, {"recall", number(f.recall)},
          {"ap50", number(f.ap50)}};
}

nlohmann::json status_json(const TrainingStatus& t) {
  return {{"state", t.state},
          {"progress", t.progress},
          {"message", t.message},
          {"train_frames", t.train_frames},
          {"test_frames", t.test_frames},
          {"samples", t.samples},
          {"positives", t.positives},
          {"seconds", t.seconds},
          {"with_general", t.with_general},
          {"general_frames", t.general_frames},
          {"trained", figures_json(t.trained)},
          {"current", figures_json(t.current)}};
}

}  // namespace

void add_training_routes(ServerState& s) {
  auto& http = s.http;
  http.Get("/api/train", [&s](const httplib::Request&, httplib::Response& res) {
    reply_json(res, status_json(s.training->status()));
  });
  http.Post("/api/train", [&s](const httplib::Request& req, httplib::Response& res) {
    const auto body = body_object(req, res);
    if (!body) return;
    const auto with_general = body->value("with_general", nlohmann::json(false));
    if (!with_general.is_boolean()) return reply_error(res, 400, "with_general must be true or false");
    if (with_general.get<bool>() && s.training->general_passes() == 0)
      return reply_error(res, 400, "no general passes: start the studio with --general-data DIR[,DIR...]");
    if (!s.training->start(s.labels->labelled(), with_general.get<bool>()))
      return reply_error(res, 409, "a training job is running");
    reply_json(res, status_json(s.training->status()), 202);
  });
  http.Post("/api/train/cancel", [&s](const httplib::Request&, httplib::Response& res) {
    s.training->cancel();
    reply_json(res, status_json(s.training->status()));
  });
  http.Post("/api/train/keep", [&s](const httplib::Request&, httplib::Response& res) {
    if (!s.writable) return reply_error(res, 403, "this studio is read-only");
    try {
      const auto file = s.training->keep(s.options.models_dir);
      reply_json(res, {{"model", file.string()}});
    } catch (const std::exception& e) {
      reply_error(res, 409, e.what());
    }
  });
  http.Post("/api/train/discard", [&s](const httplib::Request&, httplib::Response& res) {
    try {
      s.training->discard();
      reply_json(res, status_json(s.training->status()));
    } catch (const std::exception& e) {
      reply_error(res, 409, e.what());
    }
  });
}

}  // namespace cropsight::studio
