#pragma once
// Generic configuration: a config struct exposes its fields through
//
//   template <class V> void visit(V& v) {
//     v("depth_min", depth_min, "m; minimum depth kept (paper: 0.5 m, Kusumam et al. §4.1)");
//     ...
//   }
//
// and these helpers apply flat "key=value" maps (from a YAML preset, flattened with dots, and
// from --set key=value) to it, or dump it back. Unknown keys are an error, so a typo in a preset
// or on the command line never passes silently.
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "cropsight/core/error.hpp"

namespace cropsight {

/// Flat key → value text. Keys are dotted paths ("oes.depth_tolerance").
using ConfigMap = std::map<std::string, std::string>;

namespace detail {
template <typename T>
void parse_value(const std::string& where, const std::string& key, const std::string& text, T& out) {
  if constexpr (std::is_same_v<T, bool>) {
    if (text == "true" || text == "1" || text == "on" || text == "yes")
      out = true;
    else if (text == "false" || text == "0" || text == "off" || text == "no")
      out = false;
    else
      throw Error(where, "'" + key + "' expects true/false, got '" + text + "'");
  } else if constexpr (std::is_same_v<T, std::string>) {
    out = text;
  } else if constexpr (std::is_arithmetic_v<T>) {
    std::istringstream in(text);
    in.imbue(std::locale::classic());
    T v{};
    in >> v;
    if (in.fail() || !(in >> std::ws).eof()) throw Error(where, "'" + key + "' expects a number, got '" + text + "'");
    if constexpr (std::is_floating_point_v<T>) {
      if (!(v == v)) throw Error(where, "'" + key + "' is NaN");
    }
    out = v;
  } else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<int>>) {
    out.clear();
    std::string s = text;
    for (char& c : s)
      if (c == ',' || c == '[' || c == ']') c = ' ';
    std::istringstream in(s);
    in.imbue(std::locale::classic());
    typename T::value_type v;
    while (in >> v) out.push_back(v);
    if (!in.eof()) throw Error(where, "'" + key + "' expects a list of numbers, got '" + text + "'");
  } else {
    static_assert(sizeof(T) == 0, "unsupported config field type");
  }
}

template <typename T>
std::string format_value(const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    return v ? "true" : "false";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<int>>) {
    std::ostringstream o;
    o.imbue(std::locale::classic());
    o << '[';
    for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << v[i];
    o << ']';
    return o.str();
  } else {
    std::ostringstream o;
    o.imbue(std::locale::classic());
    o.precision(10);
    o << v;
    return o.str();
  }
}

struct ApplyVisitor {
  const ConfigMap& values;
  const std::string& where;
  std::string prefix;
  std::map<std::string, bool>& used;
  template <typename T>
  void operator()(const char* name, T& field, const char* /*doc*/) {
    const std::string key = prefix + name;
    if constexpr (requires { field.visit(*this); }) {
      ApplyVisitor sub{values, where, key + ".", used};
      field.visit(sub);
    } else {
      auto it = values.find(key);
      if (it != values.end()) {
        parse_value(where, key, it->second, field);
        used[key] = true;
      }
    }
  }
};

struct DumpVisitor {
  std::vector<std::tuple<std::string, std::string, std::string>>& out;  // key, value, doc
  std::string prefix;
  template <typename T>
  void operator()(const char* name, T& field, const char* doc) {
    const std::string key = prefix + name;
    if constexpr (requires { field.visit(*this); }) {
      DumpVisitor sub{out, key + "."};
      field.visit(sub);
    } else {
      out.emplace_back(key, format_value(field), doc);
    }
  }
};
}  // namespace detail

/// Applies `values` to `cfg` (keys relative to `prefix`, e.g. "detector."). Keys in `values`
/// that start with `prefix` but name no field throw Error(where, "unknown key ...").
template <typename Config>
void apply_config(Config& cfg, const ConfigMap& values, const std::string& where, const std::string& prefix = "") {
  std::map<std::string, bool> used;
  detail::ApplyVisitor v{values, where, prefix, used};
  cfg.visit(v);
  for (const auto& [key, value] : values) {
    if (key.rfind(prefix, 0) == 0 && !used.count(key)) throw Error(where, "unknown configuration key '" + key + "'");
  }
}

/// Every field as (dotted key, value text, documentation), in declaration order.
template <typename Config>
std::vector<std::tuple<std::string, std::string, std::string>> dump_config(const Config& cfg,
                                                                           const std::string& prefix = "") {
  std::vector<std::tuple<std::string, std::string, std::string>> out;
  detail::DumpVisitor v{out, prefix};
  const_cast<Config&>(cfg).visit(v);  // visit() only reads through DumpVisitor
  return out;
}

/// Parses "key=value" (from --set). Throws Error("--set", ...) when malformed.
std::pair<std::string, std::string> parse_assignment(const std::string& text);

}  // namespace cropsight
