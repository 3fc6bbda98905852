// A folder of images: the images, the model's boxes and the labels (server_state.hpp).
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "studio/image_shapes.hpp"
#include "studio/server_state.hpp"

namespace cropsight::studio {

namespace {

nlohmann::json image_info_json(const ServerState& s) {
  const ImageLabelStore& store = *s.image_labels;
  return {{"mode", "images"},
          {"folder", s.options.images.filename().string()},
          {"images", store.images()},
          {"frames", store.images().size()},
          {"model", s.proposals->model_name()},
          {"classes", store.classes()},
          {"labelled", store.labelled()},
          {"outputs", std::string(kImageLabelsFolder) + "/"},
          {"read_only", !s.writable}};
}

// The image number of the route's first group; answers 404 and returns nothing when the folder
// has no such image.
std::optional<int> image_of(const ServerState& s, const httplib::Request& req, httplib::Response& res) {
  const std::string digits = req.matches.size() > 1 ? std::string(req.matches[1]) : "";
  if (digits.empty() || digits.size() > 9 || std::stoul(digits) >= s.image_labels->images().size()) {
    reply_error(res, 404, "no image " + digits);
    return std::nullopt;
  }
  return std::stoi(digits);
}

std::string image_type(const std::string& name) {
  const std::string ext = name.substr(name.rfind('.') + 1);
  return (ext == "png" || ext == "PNG") ? "image/png" : "image/jpeg";
}

nlohmann::json proposals_json(ServerState& s, int index) {
  const auto& names = s.proposals->class_names();
  nlohmann::json out = nlohmann::json::array();
  for (const Detection2D& d : s.proposals->detect(index, s.image_labels->image_path(index))) {
    const std::string label = d.class_id >= 0 && std::size_t(d.class_id) < names.size()
                                  ? names[std::size_t(d.class_id)]
                                  : "class" + std::to_string(d.class_id);
    out.push_back({{"label", label}, {"score", d.score}, {"box", {d.x1, d.y1, d.x2, d.y2}}});
  }
  return out;
}

// POST /api/image/N/labels: {"shapes": [...]} (image_shapes.hpp).
void save_image_labels(ServerState& s, int index, const httplib::Request& req, httplib::Response& res) {
  if (!s.writable) return reply_error(res, 403, "this studio is read-only (--read-only, or another studio writes)");
  const auto [width, height] = s.image_labels->size(index);
  std::string error;
  auto shapes = parse_shapes_body(req.body, width, height, error);
  if (!shapes) return reply_error(res, 400, error);
  const std::size_t count = shapes->size();
  try {
    s.image_labels->save(index, std::move(*shapes));
  } catch (const Error& e) {
    return reply_error(res, 409, e.what());  // a file of the user's in the way, or a folder that cannot be written
  }
  reply_json(res, {{"image", index},
                   {"shapes", count},
                   {"labelled", s.image_labels->labelled()},
                   {"classes", s.image_labels->classes()}});
}

}  // namespace

void add_image_routes(ServerState& s) {
  auto& http = s.http;
  http.Get("/api/info", [&s](const httplib::Request&, httplib::Response& res) { reply_json(res, image_info_json(s)); });
  http.Get(R"(/api/image/(\d+)/pixels)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto i = image_of(s, req, res)) {
      const std::string& name = s.image_labels->images()[std::size_t(*i)];
      res.set_content(io::read_file(s.image_labels->image_path(*i)), image_type(name).c_str());
    }
  });
  http.Get(R"(/api/image/(\d+)/proposals)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto i = image_of(s, req, res)) reply_json(res, {{"image", *i}, {"shapes", proposals_json(s, *i)}});
  });
  http.Get(R"(/api/image/(\d+)/labels)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto i = image_of(s, req, res)) {
      const auto [width, height] = s.image_labels->size(*i);
      const auto labels = s.image_labels->labels(*i);
      reply_json(res, {{"image", *i},
                       {"name", s.image_labels->images()[std::size_t(*i)]},
                       {"width", width},
                       {"height", height},
                       {"labelled", labels.has_value()},
                       {"shapes", shapes_json(labels ? labels->shapes : std::vector<io::LabelShape>{})}});
    }
  });
  http.Post(R"(/api/image/(\d+)/labels)", [&s](const httplib::Request& req, httplib::Response& res) {
    if (const auto i = image_of(s, req, res)) save_image_labels(s, *i, req, res);
  });
}

}  // namespace cropsight::studio
