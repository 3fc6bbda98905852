#include "frame_times_csv.hpp"

#include <map>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "number_text.hpp"
#include "pose_text.hpp"

namespace cropsight::io::detail {

namespace fs = std::filesystem;

std::vector<double> frame_times_from_csv(const fs::path& path, const std::vector<RecordingFile>& frames) {
  const std::string where = path.string(), text = read_file(path);
  std::istringstream in(text);
  std::string line, header_text;
  std::vector<std::string_view> header;
  std::size_t frame_col = 0, time_col = 0;
  std::map<double, double> time_of;  // frame number -> seconds
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const std::string_view l = trim(line);
    if (l.empty() || l.front() == '#') continue;
    const std::string at = "line " + std::to_string(line_no) + ": ";
    if (header.empty()) {
      header_text = l;
      header = pose_fields(header_text, ',');
      std::size_t found = 0;
      for (std::size_t i = 0; i < header.size(); ++i) {
        if (header[i] == "frame") frame_col = i, found |= 1;
        if (header[i] == "timestamp") time_col = i, found |= 2;
      }
      if (found != 3) throw Error(where, at + "expected a header naming the columns 'frame' and 'timestamp'");
      continue;
    }
    const auto f = pose_fields(l, ',');
    if (f.size() != header.size())
      throw Error(where, at + "expected " + std::to_string(header.size()) + " values as in the header, got " +
                             std::to_string(f.size()));
    const double frame = pose_number(f[frame_col], "frame", line_no, path);
    if (!time_of.emplace(frame, pose_number(f[time_col], "timestamp", line_no, path)).second)
      throw Error(where, at + "frame " + std::string(f[frame_col]) + " is listed twice");
  }
  if (header.empty()) throw Error(where, "empty file (expected a header naming 'frame' and 'timestamp')");
  std::vector<double> out;
  for (const RecordingFile& file : frames) {
    const auto t = time_of.find(file.value);
    if (t == time_of.end())
      throw Error(where, "no row for frame " + file.key + " (" + file.path.filename().string() + ")");
    if (!out.empty() && !(t->second > out.back()))
      throw Error(where, "the time of frame " + file.key + " (" + format_double(t->second) +
                             " s) does not increase from the frame before");
    out.push_back(t->second);
  }
  return out;
}

}  // namespace cropsight::io::detail
