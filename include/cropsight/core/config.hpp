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
//
// Field types: bool, std::string, arithmetic, std::vector<double|int>, and enums that declare
// their spellings with a free function found by argument-dependent lookup,
//
//   enum class Variant { oes, org, fec };
//   constexpr std::array<const char*, 3> config_names(Variant) { return {"oes", "org", "fec"}; }
//
// (index = enumerator value), so that a preset says "oes" while the code switches on the enum.
//
// A numeric field may declare its valid range where it is declared, as a fourth argument:
//
//   v("min_points", min_points, "points; ...", Range::at_least(1));
//   v("subsample", subsample, "fraction; ...", Range::within(0.0, 1.0).open_below());
//
// apply_config checks the values it sets (the error names the preset or "--set" and the key) and
// check_config checks every field (for values set in code), so a struct's validate() keeps only
// the rules that tie fields together.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <locale>
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
/// A number as configs and their errors print it: classic locale, 10 significant digits.
template <typename T>
std::string format_number(T v) {
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o.precision(10);
  o << v;
  return o.str();
}
/// A double as text that reads back to the same value (17 significant digits, classic locale):
/// what a fitted value written into a config or a model file keeps.
inline std::string exact_number(double v) {
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o.precision(17);
  o << v;
  return o.str();
}
}  // namespace detail

/// The valid range of a numeric config field (see above): [lo, hi], either end open or infinite;
/// `why` (optional) is appended to the error in parentheses. Values must also be finite (NaN is
/// refused by the parser already; ±inf here). Range{} = any finite value.
struct Range {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  const char* why = "";
  /// Integer fields: the value must be `remainder` modulo `step` (step 0 = no such rule), e.g.
  /// odd window sides, or disparity ranges in multiples of 16.
  int step = 0, remainder = 0;

  static constexpr Range at_least(double v, const char* why = "") {
    return {v, std::numeric_limits<double>::infinity(), false, false, why};
  }
  static constexpr Range above(double v, const char* why = "") {
    return {v, std::numeric_limits<double>::infinity(), true, false, why};
  }
  static constexpr Range at_most(double v, const char* why = "") {
    return {-std::numeric_limits<double>::infinity(), v, false, false, why};
  }
  static constexpr Range within(double a, double b, const char* why = "") { return {a, b, false, false, why}; }
  constexpr Range open_below() const { return with_ends(true, hi_open); }
  constexpr Range open_above() const { return with_ends(lo_open, true); }
  /// Integer fields only: the value must also be odd / a multiple of k.
  constexpr Range odd() const { return with_step(2, 1); }
  constexpr Range multiple_of(int k) const { return with_step(k, 0); }

  bool contains(double v) const { return violation(v).empty(); }
  /// "" when `v` is inside; else the rule it breaks: "must be at least 3 (why)".
  std::string violation(double v) const {
    std::string rule;
    if (!std::isfinite(v))
      rule = "must be finite";
    else if (lo_open ? !(v > lo) : !(v >= lo))
      rule = std::string(lo_open ? "must be greater than " : "must be at least ") + number(lo);
    else if (hi_open ? !(v < hi) : !(v <= hi))
      rule = std::string(hi_open ? "must be less than " : "must be at most ") + number(hi);
    else if (step > 0 && (v != std::floor(v) || ((long long)v % step + step) % step != remainder))
      rule = "must be " + step_rule();
    if (!rule.empty() && why[0] != '\0') rule += std::string(" (") + why + ")";
    return rule;
  }
  /// The whole rule, for documentation: "at least 1", "in (0, 1]", "finite", "odd, in [1, 9]".
  std::string rule() const {
    const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
    const std::string prefix = step > 0 ? step_rule() + ", " : "";
    if (!has_lo && !has_hi) return step > 0 ? step_rule() : "finite";
    if (!has_hi) return prefix + (lo_open ? "greater than " : "at least ") + number(lo);
    if (!has_lo) return prefix + (hi_open ? "less than " : "at most ") + number(hi);
    return prefix + "in " + (lo_open ? "(" : "[") + number(lo) + ", " + number(hi) + (hi_open ? ")" : "]");
  }

 private:
  constexpr Range with_ends(bool lo_o, bool hi_o) const { return {lo, hi, lo_o, hi_o, why, step, remainder}; }
  constexpr Range with_step(int k, int r) const { return {lo, hi, lo_open, hi_open, why, k, r}; }
  std::string step_rule() const {
    if (step == 2) return remainder == 1 ? "odd" : "even";
    return "a multiple of " + std::to_string(step) + (remainder ? " plus " + std::to_string(remainder) : "");
  }
  static std::string number(double v) { return detail::format_number(v); }
};

/// An enum field: its spellings come from config_names(T{}) (see above).
template <typename T>
concept ConfigEnum = std::is_enum_v<T> && requires {
  config_names(T{});
};

/// The spelling of an enum value ("?" for a value outside the table).
template <ConfigEnum T>
std::string config_name(T value) {
  const auto names = config_names(T{});
  const auto i = static_cast<std::size_t>(value);
  return i < names.size() ? names[i] : "?";
}

namespace detail {
template <ConfigEnum T>
std::string enum_choices() {
  std::string out;
  for (const char* n : config_names(T{})) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

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
  } else if constexpr (ConfigEnum<T>) {
    const auto names = config_names(T{});
    for (std::size_t i = 0; i < names.size(); ++i)
      if (text == names[i]) {
        out = static_cast<T>(i);
        return;
      }
    throw Error(where, "'" + key + "' expects one of " + enum_choices<T>() + ", got '" + text + "'");
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
  } else if constexpr (ConfigEnum<T>) {
    return config_name(v);
  } else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<int>>) {
    std::ostringstream o;
    o.imbue(std::locale::classic());
    o << '[';
    for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << v[i];
    o << ']';
    return o.str();
  } else {
    return format_number(v);
  }
}

template <typename T>
void check_range(const std::string& where, const std::string& key, const T& value, const Range& range) {
  static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, "a Range needs a numeric field");
  if (const std::string rule = range.violation(double(value)); !rule.empty())
    throw Error(where, "'" + key + "' " + rule + ", got " + format_value(value));
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
  template <typename T>
  void operator()(const char* name, T& field, const char* doc, const Range& range) {
    (*this)(name, field, doc);
    if (values.count(prefix + name)) check_range(where, prefix + name, field, range);
  }
};

struct CheckVisitor {
  const std::string& where;
  std::string prefix;
  template <typename T>
  void operator()(const char* name, T& field, const char* /*doc*/) {
    if constexpr (requires { field.visit(*this); }) {
      CheckVisitor sub{where, prefix + name + "."};
      field.visit(sub);
    }
  }
  template <typename T>
  void operator()(const char* name, T& field, const char* /*doc*/, const Range& range) {
    check_range(where, prefix + name, field, range);
  }
};

struct DumpVisitor {
  std::vector<std::tuple<std::string, std::string, std::string>>& out;  // key, value, doc
  std::string prefix;
  template <typename T>
  void operator()(const char* name, T& field, const char* doc, const Range& range) {
    out.emplace_back(prefix + name, format_value(field), std::string(doc) + " (" + range.rule() + ")");  // docs only
  }
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

/// Checks every field that declares a Range; throws Error(where, "'key' must be ..., got ...").
template <typename Config>
void check_config(const Config& cfg, const std::string& where, const std::string& prefix = "") {
  detail::CheckVisitor v{where, prefix};
  const_cast<Config&>(cfg).visit(v);  // visit() only reads through CheckVisitor
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
