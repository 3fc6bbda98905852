#include "ply_check.hpp"

#include <cstdint>
#include <cstdlib>
#include <set>
#include <sstream>
#include <vector>

#include "cropsight/core/error.hpp"

namespace cropsight::io::detail {
namespace {

// Bytes of a PLY scalar type; 0 for an unknown name.
int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}
bool is_integer_type(const std::string& t) {
  return type_size(t) > 0 && t.find("float") == std::string::npos && t != "double";
}

struct Property {
  std::string name;
  int size = 0;        // scalar bytes, or the list items' bytes
  int count_size = 0;  // list only: bytes of the item count
  bool is_signed_count = false;
  std::string type;  // scalar only: the PLY type name
};
struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

// PCL reads element counts into an int; far more elements than bytes is caught by the data walk.
std::uint64_t parse_count(const std::string& text, const std::string& where, int line) {
  if (text.empty() || text.size() > 10 || text.find_first_not_of("0123456789") != std::string::npos)
    throw Error(where, "PLY header line " + std::to_string(line) + ": element count '" + text + "' is not a count");
  const std::uint64_t n = std::strtoull(text.c_str(), nullptr, 10);
  if (n > 0x7fffffffull) throw Error(where, "PLY header line " + std::to_string(line) + ": element count too large");
  return n;
}

std::uint64_t read_list_count(const unsigned char* p, int size, bool big_endian, bool is_signed) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) v |= std::uint64_t(p[big_endian ? i : size - 1 - i]) << (8 * (size - 1 - i));
  if (is_signed && size < 8 && (v >> (8 * size - 1)) & 1) return UINT64_MAX;  // negative: no valid count
  return v;
}

}  // namespace

// Long on purpose: the PLY header rules in the order the format states them, each with its own error line.
void check_ply(const std::string& bytes, const std::string& where) {
  std::size_t pos = 0;
  int line_no = 0;
  auto next_line = [&](std::string& line) {
    if (pos >= bytes.size()) return false;
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    line = bytes.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = std::min(bytes.size(), end + 1);
    ++line_no;
    return true;
  };
  auto fail = [&](const std::string& what) {
    throw Error(where, "malformed PLY header, line " + std::to_string(line_no) + ": " + what);
  };
  auto fail_data = [&](const std::string& what) {
    throw Error(where, "malformed PLY data, line " + std::to_string(line_no) + ": " + what);
  };
  std::string line;
  if (!next_line(line) || line != "ply") throw Error(where, "not a PLY file (the first line must be 'ply')");
  std::string format;
  std::vector<Element> elements;
  bool ended = false;
  while (next_line(line)) {
    // PCL's PLY parser and its callbacks split header lines differently (on any whitespace, or on
    // spaces only): a carriage return inside a line made its obj_info callback assert (fuzz_ply).
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') fail("a control character in a header line");
    const auto t = tokens(line);
    if (t.empty()) fail("empty line");
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") {
      if (t.size() != 1) fail("'end_header' takes nothing after it");
      ended = true;
      break;
    }
    if (t[0] == "format") {
      if (!format.empty()) fail("a second format line");
      if (t.size() != 3 || t[2] != "1.0" ||
          (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      format = t[1];
    } else if (t[0] == "element") {
      if (t.size() != 3) fail("expected 'element NAME COUNT'");
      for (const auto& e : elements)
        if (e.name == t[1]) fail("element '" + t[1] + "' declared twice");
      elements.push_back({t[1], parse_count(t[2], where, line_no), {}});
    } else if (t[0] == "property") {
      if (elements.empty()) fail("a property before any element");
      Property p;
      if (t.size() >= 2 && t[1] == "list") {
        if (t.size() != 5 || !is_integer_type(t[2]) || type_size(t[3]) == 0)
          fail("expected 'property list COUNT_TYPE ITEM_TYPE NAME' with an integer COUNT_TYPE");
        p = {t[4], type_size(t[3]), type_size(t[2]), t[2][0] != 'u', {}};
      } else {
        if (t.size() != 3 || type_size(t[1]) == 0) fail("expected 'property TYPE NAME' with a PLY scalar type");
        p = {t[2], type_size(t[1]), 0, false, t[1]};
      }
      for (const auto& q : elements.back().properties)
        if (q.name == p.name) fail("property '" + p.name + "' declared twice");
      elements.back().properties.push_back(p);
    } else {
      fail("unknown keyword '" + t[0] + "'");
    }
  }
  if (!ended) throw Error(where, "malformed PLY header: no 'end_header' line");
  if (format.empty()) throw Error(where, "malformed PLY header: no format line");
  // PCL packs a vertex's red, green and blue into one rgb field created at "red" and filled by
  // all three: a green or blue without the red before it wrote past the point and hit an assert
  // (fuzz_ply; fuzz/regressions/ply/). So colour comes as red, green, blue (uchar, in that
  // order, one after the other), and alpha only right after blue.
  for (const auto& e : elements) {
    if (e.name != "vertex") continue;
    const auto& ps = e.properties;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const std::string& n = ps[i].name;
      if (n != "red" && n != "green" && n != "blue" && n != "alpha") continue;
      const auto is = [&](std::size_t k, const char* name) {
        return k < ps.size() && ps[k].name == name && ps[k].count_size == 0 &&
               (ps[k].type == "uchar" || ps[k].type == "uint8");
      };
      if (!(is(i, "red") && is(i + 1, "green") && is(i + 2, "blue")))
        throw Error(where, "malformed PLY header: vertex colour must be uchar red, green, blue in that order");
      i += 2;
      if (is(i + 1, "alpha")) ++i;
    }
  }

  // The body: every element instance in declaration order.
  if (format == "ascii") {
    for (const auto& e : elements) {
      for (std::uint64_t i = 0; i < e.count; ++i) {
        std::string data;
        do {
          if (!next_line(data))
            throw Error(where, "PLY data ends early: element '" + e.name + "' has " + std::to_string(e.count) +
                                   " entries in the header, the file " + std::to_string(i));
        } while (tokens(data).empty());
        const auto values = tokens(data);
        std::size_t k = 0;  // values this instance has according to the header
        for (const auto& p : e.properties) {
          if (p.count_size == 0 || k >= values.size()) {
            ++k;
            continue;
          }
          char* end = nullptr;
          const long n = std::strtol(values[k].c_str(), &end, 10);
          if (*end != '\0' || n < 0 || std::uint64_t(n) > values.size())
            fail_data("bad list count '" + values[k] + "'");
          k += 1 + std::size_t(n);
        }
        if (k != values.size())
          fail_data(std::to_string(values.size()) + " values where element '" + e.name + "' has " + std::to_string(k));
        for (const auto& v : values) {
          char* end = nullptr;
          std::strtod(v.c_str(), &end);
          if (*end != '\0') fail_data("'" + v + "' is not a number");
        }
      }
    }
    return;
  }
  const bool big_endian = format == "binary_big_endian";
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  std::uint64_t at = pos;
  const std::uint64_t size = bytes.size();
  auto ends_early = [&](const Element& e) {
    throw Error(where, "PLY data ends early: element '" + e.name + "' needs more bytes than the file has");
  };
  for (const auto& e : elements) {
    std::uint64_t fixed = 0;  // bytes of an instance without lists
    bool lists = false;
    for (const auto& p : e.properties) {
      if (p.count_size)
        lists = true;
      else
        fixed += std::uint64_t(p.size);
    }
    if (!lists) {  // one check for the whole element
      if (fixed != 0 && e.count > (size - at) / fixed) ends_early(e);
      at += e.count * fixed;
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const auto& p : e.properties) {
        const std::uint64_t step = std::uint64_t(p.count_size ? p.count_size : p.size);
        if (step > size - at) ends_early(e);
        if (!p.count_size) {
          at += step;
          continue;
        }
        const std::uint64_t n = read_list_count(data + at, p.count_size, big_endian, p.is_signed_count);
        at += step;
        if (n == UINT64_MAX || n > (size - at) / std::uint64_t(p.size)) ends_early(e);
        at += n * std::uint64_t(p.size);
      }
    }
  }
}

}  // namespace cropsight::io::detail
