#include "pcd_check.hpp"

#include <cstdint>
#include <sstream>
#include <vector>

#include "cropsight/core/error.hpp"

namespace cropsight::io::detail {

namespace {

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// A plain decimal integer in [lo, hi]; false for anything else (signs, exponents, overflow).
bool integer(const std::string& s, std::uint64_t lo, std::uint64_t hi, std::uint64_t& v) {
  if (s.empty() || s.size() > 19) return false;
  v = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + std::uint64_t(c - '0');
  }
  return v >= lo && v <= hi;
}

// The header keyword PCL 1.13's PCDReader::readHeader takes a line's first word for: it compares
// prefixes ("FIELDSX" is FIELDS, "COLUMNS" is FIELDS too). Empty when it is none (PCL stops).
std::string pcl_keyword(const std::string& first) {
  if (first[0] == '#') return "#";
  static const char* const keys[][2] = {{"VERSION", "VERSION"}, {"FIELDS", "FIELDS"}, {"COLUMNS", "FIELDS"},
                                        {"SIZE", "SIZE"},       {"TYPE", "TYPE"},     {"COUNT", "COUNT"},
                                        {"WIDTH", "WIDTH"},     {"HEIGHT", "HEIGHT"}, {"VIEWPOINT", "VIEWPOINT"},
                                        {"POINTS", "POINTS"},   {"DATA", "DATA"}};
  for (const auto& k : keys)
    if (first.rfind(k[0], 0) == 0) return k[1];
  return {};
}

}  // namespace

// Long on purpose: the PCD header fields in the order the format requires them, each with its own error line.
void check_pcd_header(const std::string& bytes, const std::string& where) {
  const auto fail = [&](int line, const std::string& problem) {
    throw Error(where, "malformed PCD header, line " + std::to_string(line) + ": " + problem);
  };
  std::size_t fields = 0, pos = 0;
  std::vector<std::uint64_t> sizes, counts;
  std::uint64_t width = 0, height = 0, points = 0;
  bool have_fields = false, have_types = false, have_width = false, have_height = false, have_points = false;
  std::string data;
  std::size_t body_start = 0;
  int line_no = 0;
  // PCL's loop: every line is read as a header line until one whose first word is not a keyword,
  // and that includes the lines after DATA (DATA only records where the body starts), so bytes
  // of the body that read as "COLUMNS ..." or "SIZE ..." redefine the fields after our checks.
  while (pos < bytes.size()) {
    const std::size_t end = std::min(bytes.find('\n', pos), bytes.size());
    const std::string line = bytes.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (line.empty()) continue;  // PCL skips only empty lines; a line of blanks ends its header
    const auto w = words(line);
    if (w.empty()) break;
    const std::string key = pcl_keyword(w[0]);
    if (key.empty()) {  // where PCL stops reading the header: the body, or a line it does not know
      if (data.empty()) fail(line_no, "'" + w[0].substr(0, 40) + "' is not a PCD header keyword (before DATA)");
      break;
    }
    if (key == "#" || key == "VERSION") continue;
    if (!data.empty())
      fail(line_no, "a line after DATA that PCL reads as header ('" + key + "'): a damaged or concatenated file");
    // PCL splits the words on spaces, tabs and CRs, and reads the numbers from a stream, which
    // also splits on vertical tabs and form feeds: with those the two would disagree.
    if (line.find_first_of("\v\f") != std::string::npos) fail(line_no, "vertical tab or form feed in a header line");
    const std::size_t n = w.size() - 1;
    std::uint64_t v = 0;
    // PCL sizes the point buffer when it reads POINTS, from the point size known then: fields
    // defined after it would be written past the buffer (readBodyASCII; fuzz_pcd).
    if (have_points && (key == "FIELDS" || key == "SIZE" || key == "TYPE" || key == "COUNT"))
      fail(line_no, key + " after POINTS (PCL sizes the points at POINTS)");
    if (key == "FIELDS") {
      if (have_fields) fail(line_no, "FIELDS given twice");
      if (n == 0) fail(line_no, "FIELDS names no field");
      fields = n;
      have_fields = true;
    } else if (key == "SIZE" || key == "TYPE" || key == "COUNT") {
      if (!have_fields) fail(line_no, key + " before FIELDS");
      if (n != fields)
        fail(line_no, key + " has " + std::to_string(n) + " entries for " + std::to_string(fields) + " fields");
      std::vector<std::uint64_t>* out = key == "SIZE" ? &sizes : key == "COUNT" ? &counts : nullptr;
      if (key == "TYPE" ? have_types : !out->empty()) fail(line_no, key + " given twice");
      if (key == "TYPE") have_types = true;
      for (std::size_t i = 1; i <= n; ++i) {
        if (key == "TYPE") {
          if (w[i] != "I" && w[i] != "U" && w[i] != "F") fail(line_no, "TYPE '" + w[i] + "' is not I, U or F");
          // PCL copies a value of its type's size: F of SIZE 1 or 2 has none, and a missing TYPE
          // line leaves every field a 4-byte float whatever its SIZE.
          if (sizes.empty()) fail(line_no, "TYPE before SIZE");
          if (w[i] == "F" && sizes[i - 1] != 4 && sizes[i - 1] != 8)
            fail(line_no,
                 "TYPE F of field " + std::to_string(i) + " needs SIZE 4 or 8, not " + std::to_string(sizes[i - 1]));
        } else if (key == "SIZE") {
          if (!integer(w[i], 1, 8, v) || (v != 1 && v != 2 && v != 4 && v != 8))
            fail(line_no, "SIZE '" + w[i] + "' is not 1, 2, 4 or 8");
          out->push_back(v);
        } else {
          if (!integer(w[i], 1, 1u << 20, v)) fail(line_no, "COUNT '" + w[i] + "' is not 1 to 1048576");
          out->push_back(v);
        }
      }
    } else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS") {
      bool& have = key == "WIDTH" ? have_width : key == "HEIGHT" ? have_height : have_points;
      if (have) fail(line_no, key + " given twice");
      if (n != 1 || !integer(w[1], 0, 0x7fffffffu, v)) fail(line_no, key + " is not one integer from 0 to 2^31 - 1");
      (key == "WIDTH" ? width : key == "HEIGHT" ? height : points) = v;
      have = true;
    } else if (key == "DATA") {
      if (n != 1) fail(line_no, "DATA takes one word (ascii, binary or binary_compressed)");
      data = w[1];
      if (data != "ascii" && data != "binary" && data != "binary_compressed")
        fail(line_no, "DATA '" + data + "' is not ascii, binary or binary_compressed");
      body_start = std::min(pos, bytes.size());
    }
    // VIEWPOINT is PCL's to check.
  }
  if (data.empty()) throw Error(where, "malformed PCD header: no DATA line");
  if (!have_fields || sizes.size() != fields || !have_types || !have_width || !have_points)
    throw Error(where, "malformed PCD header (needs FIELDS, SIZE, TYPE, COUNT, WIDTH, HEIGHT, POINTS, DATA)");
  if (counts.empty()) counts.assign(fields, 1);  // COUNT is optional: 1 each
  if (!have_height) height = 1;
  if (points != width * height)
    throw Error(where, "malformed PCD header: POINTS " + std::to_string(points) + " is not WIDTH x HEIGHT");
  std::uint64_t values = 0, step = 0;
  for (std::size_t i = 0; i < fields; ++i) values += counts[i], step += counts[i] * sizes[i];
  const unsigned __int128 body = bytes.size() - body_start;
  const unsigned __int128 need = data == "ascii"    ? (unsigned __int128)points * values * 2
                                 : data == "binary" ? (unsigned __int128)points * step
                                                    : 0;
  if (need > body || (data == "binary_compressed" && (unsigned __int128)points * step > ((unsigned __int128)1 << 30)))
    throw Error(where, "PCD header declares " + std::to_string(points) + " points, more than the file can hold");
  if (data == "binary_compressed") {
    // PCL resizes the points to the uncompressed size the body declares, then writes every point
    // the header declares into them: the two must agree.
    if (body < 8) throw Error(where, "binary_compressed PCD body shorter than its 8-byte size header");
    const auto u32 = [&](std::size_t at) {
      std::uint64_t v = 0;
      for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(bytes[at + std::size_t(k)]);
      return v;
    };
    const std::uint64_t compressed = u32(body_start), uncompressed = u32(body_start + 4);
    if (uncompressed != points * step)
      throw Error(where, "binary_compressed PCD declares " + std::to_string(uncompressed) +
                             " bytes uncompressed; its header's points take " + std::to_string(points * step));
    if (compressed > body - 8)
      throw Error(where, "binary_compressed PCD declares " + std::to_string(compressed) +
                             " compressed bytes, more than the file holds");
  }
}

}  // namespace cropsight::io::detail
