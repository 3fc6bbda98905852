// VOC XML through tinyxml2 (a real parser: entities, comments and attribute order are its
// business, not ours) and the paper's detection text format with strict line checks.
#include "cropsight/io/voc.hpp"

#include <tinyxml2.h>

#include <cstdio>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "number_text.hpp"

namespace cropsight::io {
namespace fs = std::filesystem;

namespace {

const char* child_text(const tinyxml2::XMLElement* parent, const char* name) {
  const tinyxml2::XMLElement* e = parent->FirstChildElement(name);
  return e && e->GetText() ? e->GetText() : nullptr;
}

// A required number: `what` names the element path in the error ("object 2 <bndbox>/<xmin>").
double required_number(const std::string& where, const tinyxml2::XMLElement* parent, const char* name,
                       const std::string& what) {
  const tinyxml2::XMLElement* e = parent->FirstChildElement(name);
  if (!e) throw Error(where, what + ": missing <" + name + ">");
  const char* text = e->GetText();
  const auto v = text ? detail::parse_double(text) : std::nullopt;
  if (!v) throw Error(where, what + ": <" + name + "> is not a number ('" + (text ? text : "") + "')");
  return *v;
}

int optional_int(const std::string& where, const tinyxml2::XMLElement* parent, const char* name,
                 const std::string& what) {
  const tinyxml2::XMLElement* e = parent->FirstChildElement(name);
  if (!e) return 0;
  const char* text = e->GetText();
  const auto v = text ? detail::parse_int(text) : std::nullopt;
  if (!v) throw Error(where, what + ": <" + name + "> is not an integer ('" + (text ? text : "") + "')");
  return int(*v);
}

}  // namespace

VocAnnotation read_voc(const fs::path& path) {
  const std::string where = path.string();
  if (fs::is_directory(path)) throw Error(where, "is a directory, expected a VOC XML file");
  const std::string text = read_file(path);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
    throw Error(where,
                std::string("malformed XML at line ") + std::to_string(doc.ErrorLineNum()) + ": " + doc.ErrorName());
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "annotation")
    throw Error(where, std::string("root element is <") + (root ? root->Name() : "") + ">, expected <annotation>");

  VocAnnotation out;
  if (const char* f = child_text(root, "filename")) out.filename = f;
  if (const tinyxml2::XMLElement* size = root->FirstChildElement("size")) {
    out.width = optional_int(where, size, "width", "<size>");
    out.height = optional_int(where, size, "height", "<size>");
    out.depth = optional_int(where, size, "depth", "<size>");
  }
  int index = 0;
  for (const tinyxml2::XMLElement* obj = root->FirstChildElement("object"); obj;
       obj = obj->NextSiblingElement("object")) {
    const std::string what = "object " + std::to_string(++index);
    VocObject o;
    const char* name = child_text(obj, "name");
    if (!name) throw Error(where, what + ": missing <name>");
    o.name = detail::trim(name);
    o.difficult = optional_int(where, obj, "difficult", what) != 0;
    const tinyxml2::XMLElement* box = obj->FirstChildElement("bndbox");
    if (!box) throw Error(where, what + ": missing <bndbox>");
    const std::string bw = what + " <bndbox>";
    o.xmin = required_number(where, box, "xmin", bw);
    o.ymin = required_number(where, box, "ymin", bw);
    o.xmax = required_number(where, box, "xmax", bw);
    o.ymax = required_number(where, box, "ymax", bw);
    if (o.xmax < o.xmin) throw Error(where, bw + ": <xmax> is less than <xmin>");
    if (o.ymax < o.ymin) throw Error(where, bw + ": <ymax> is less than <ymin>");
    out.objects.push_back(std::move(o));
  }
  return out;
}

std::vector<DetectionLine> read_detection_text(const fs::path& path) {
  const std::string where = path.string();
  if (fs::is_directory(path)) throw Error(where, "is a directory, expected a detection text file");
  const std::string text = read_file(path);
  std::vector<DetectionLine> out;
  std::istringstream in(text);
  std::string line;
  long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string at = "line " + std::to_string(line_no) + ": ";
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string s; fields >> s;) f.push_back(s);
    if (f.empty()) continue;
    if (f.size() != 6)
      throw Error(where, at + "expected 6 fields 'label score x1 y1 x2 y2', got " + std::to_string(f.size()));
    double v[5];
    static const char* names[5] = {"score", "x1", "y1", "x2", "y2"};
    for (int i = 0; i < 5; ++i) {
      const auto p = detail::parse_double(f[std::size_t(i) + 1]);
      if (!p) throw Error(where, at + names[i] + " is not a number ('" + f[std::size_t(i) + 1] + "')");
      v[i] = *p;
    }
    if (v[3] < v[1]) throw Error(where, at + "x2 is less than x1");
    if (v[4] < v[2]) throw Error(where, at + "y2 is less than y1");
    out.push_back({f[0], v[0], v[1], v[2], v[3], v[4]});
  }
  return out;
}

std::string format_detection_text(const std::vector<Detection2D>& dets, const std::vector<std::string>& class_names) {
  std::string out;
  char buf[160];
  for (const Detection2D& d : dets) {
    const std::string label = d.class_id >= 0 && std::size_t(d.class_id) < class_names.size()
                                  ? class_names[std::size_t(d.class_id)]
                                  : "class" + std::to_string(d.class_id);
    std::snprintf(buf, sizeof buf, " %.8g %.6g %.6g %.6g %.6g\n", double(d.score), double(d.x1), double(d.y1),
                  double(d.x2), double(d.y2));
    out += label + buf;
  }
  return out;
}

void write_detection_text(const fs::path& path, const std::vector<Detection2D>& dets,
                          const std::vector<std::string>& class_names) {
  write_file_atomic(path, format_detection_text(dets, class_names));
}

}  // namespace cropsight::io
