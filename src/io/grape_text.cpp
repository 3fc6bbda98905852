// Loader for the grape dataset's text clouds. Hand-written parser (std::from_chars) because
// the shared set has ~2.4 M lines and iostreams would dominate the load time.
#include "cropsight/io/grape_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::io {
namespace fs = std::filesystem;

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == ','; }
constexpr int kMaxLabel = 5;  // the dataset's classes are 0-5
// "9", "300", "1.5": a value as the user wrote it, not std::to_string's "300.000000".
std::string shortest(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(v));
  return buf;
}
}  // namespace

Cloud read_grape_text(const fs::path& path) {
  const std::string where = path.string();
  // An ifstream opens a directory without complaint and reads nothing ("no points").
  if (fs::is_directory(path)) throw Error(where, "is a directory, expected a text cloud file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(where, "cannot open file");
  std::ostringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();

  Cloud cloud;
  cloud.points.reserve(text.size() / 80);
  cloud.normals.reserve(text.size() / 80);
  cloud.colors.reserve(text.size() / 80);
  cloud.labels.reserve(text.size() / 80);
  const char* p = text.data();
  const char* end = p + text.size();
  long line_no = 0;
  while (p < end) {
    ++line_no;
    const char* eol = std::find(p, end, '\n');
    float v[10];
    int n = 0;
    const char* q = p;
    while (true) {
      while (q < eol && is_space(*q)) ++q;
      if (q >= eol) break;
      if (n == 10) throw Error(where, "line " + std::to_string(line_no) + ": more than 10 numbers");
      float value = 0.f;
      auto [next, ec] = std::from_chars(q, eol, value);
      if (ec != std::errc() || (next < eol && !is_space(*next))) {
        const char* tok_end = q;
        while (tok_end < eol && !is_space(*tok_end)) ++tok_end;
        throw Error(where, "line " + std::to_string(line_no) + ": not a number: '" + std::string(q, tok_end) + "'");
      }
      if (!std::isfinite(value))
        throw Error(where, "line " + std::to_string(line_no) + ": value " + std::to_string(n + 1) + " is not finite");
      v[n++] = value;
      q = next;
    }
    p = eol < end ? eol + 1 : end;
    if (n == 0) continue;  // blank line (e.g. trailing newline)
    if (n != 10)
      throw Error(where, "line " + std::to_string(line_no) +
                             ": expected 10 numbers (x y z nx ny nz r g b label), got " + std::to_string(n));
    const float label = v[9];
    if (label < 0 || label != std::floor(label))
      throw Error(where, "line " + std::to_string(line_no) + ": label " + std::to_string(label) +
                             " is not a non-negative integer");
    // The dataset has six classes; a larger label would otherwise surface far from this file,
    // as "label out of range" in training or evaluation.
    if (label > float(kMaxLabel))
      throw Error(where, "line " + std::to_string(line_no) + ": label " + shortest(label) +
                             " is not a class of the dataset (0-" + std::to_string(kMaxLabel) + ")");
    // Colours are stored in [0, 1] (the dataset's, and roi-cloud's, r/255); 0-255 colours would
    // silently dominate the colour features.
    for (int k = 6; k < 9; ++k)
      if (v[k] < 0.f || v[k] > 1.f)
        throw Error(where,
                    "line " + std::to_string(line_no) + ": colour value " + shortest(v[k]) + " is outside [0, 1]");
    cloud.points.emplace_back(v[0], v[1], v[2]);
    cloud.normals.emplace_back(v[3], v[4], v[5]);
    cloud.colors.emplace_back(v[6], v[7], v[8]);
    cloud.labels.push_back(int(label));
  }
  if (cloud.points.empty()) throw Error(where, "no points");
  return cloud;
}

void write_grape_text(const fs::path& path, const Cloud& cloud) {
  cloud.validate(path.string());
  std::string out;
  out.reserve(cloud.size() * 90);
  char line[256];
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    const Eigen::Vector3f n = cloud.has_normals() ? cloud.normals[i] : Eigen::Vector3f::Zero();
    const Eigen::Vector3f c = cloud.has_colors() ? cloud.colors[i] : Eigen::Vector3f::Zero();
    const int l = cloud.has_labels() ? cloud.labels[i] : 0;
    const int len = std::snprintf(line, sizeof line, "%.6f %.6f %.6f %.6f %.6f %.6f %.6f %.6f %.6f %d.000000\n", p.x(),
                                  p.y(), p.z(), n.x(), n.y(), n.z(), c.x(), c.y(), c.z(), l);
    out.append(line, std::size_t(len));
  }
  write_file_atomic(path, out);
}

std::vector<fs::path> list_grape_clouds(const fs::path& dir) {
  const std::string where = dir.string();
  if (!fs::is_directory(dir))
    throw Error(where, "not a directory (unpack .tar.gz archives with scripts/unpack-grape.sh)");
  fs::path d = dir;
  if (fs::is_directory(dir / "points")) d = dir / "points";
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(d))
    if (e.is_regular_file() && e.path().extension() == ".txt") files.push_back(e.path());
  if (files.empty()) throw Error(where, "no .txt point clouds found (directly or under points/)");
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace cropsight::io
