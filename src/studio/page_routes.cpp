// The checks before every request (Host, token) and the page's own files (server_state.hpp).
#include "cropsight/io/files.hpp"
#include "cropsight/studio/access.hpp"
#include "cropsight/studio/sequence_files.hpp"
#include "studio/server_state.hpp"
#include "studio/web_assets.hpp"

namespace cropsight::studio {

namespace {

std::string content_type(std::string_view name) {
  auto ends = [&](std::string_view ext) {
    return name.size() >= ext.size() && name.substr(name.size() - ext.size()) == ext;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".png")) return "image/png";
  if (ends(".json")) return "application/json";
  if (ends(".yaml") || ends(".csv")) return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

}  // namespace

void add_access_checks(ServerState& s) {
  s.http.set_pre_routing_handler([&s](const httplib::Request& req, httplib::Response& res) {
    using R = httplib::Server::HandlerResponse;
    if (!host_allowed(req.get_header_value("Host"), s.port, s.options.bind)) {
      reply_error(res, 403, "this studio answers only requests addressed to localhost with its port");
      return R::Handled;
    }
    const std::string cookie = token_cookie_name(s.port);
    const std::string& token = s.options.token;
    if (same_token(req.get_param_value("token"), token)) {
      // The printed URL: the token becomes a cookie (the page's later requests carry it), and
      // the page reloads without it in the address bar.
      res.set_header("Set-Cookie", cookie + "=" + token + "; Path=/; HttpOnly; SameSite=Strict");
      if (req.method == "GET" && req.path == "/") {
        res.set_redirect("/", 303);
        return R::Handled;
      }
      return R::Unhandled;
    }
    if (same_token(cookie_value(req.get_header_value("Cookie"), cookie), token) ||
        same_token(req.get_header_value("X-Cropsight-Token"), token))
      return R::Unhandled;
    reply_error(res, 403, "no valid token: open the URL cropsight studio printed");
    return R::Handled;
  });
}

void add_page_routes(ServerState& s) {
  // A folder of images has its own page (images.html): boxes and polygons, not depth clusters.
  const std::string home = s.images_mode() ? "images.html" : "index.html";
  s.http.Get(R"(/([a-z_]*\.?[a-z]*))", [home](const httplib::Request& req, httplib::Response& res) {
    const std::string name = req.matches[1].str().empty() ? home : req.matches[1].str();
    for (const auto& asset : web_assets())
      if (asset.name == name) return res.set_content(std::string(asset.bytes), content_type(name).c_str());
    reply_error(res, 404, "no such page file");
  });
  s.http.Get(R"(/files/(.*))", [&s](const httplib::Request& req, httplib::Response& res) {
    const auto file = file_in_sequence(s.root(), req.matches[1].str());
    if (!file) return reply_error(res, 404, "no such file in the sequence");
    res.set_content(io::read_file(*file), content_type(file->filename().string()).c_str());
  });
}

}  // namespace cropsight::studio
