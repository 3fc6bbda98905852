#pragma once
// Ranges declared with a config field in visit(), so that a field's bounds live on the same line
// as its name and documentation instead of in a hand-written validate() with its own `fail`
// lambda:
//
//   template <class V> void visit(V& v) {
//     config_field(v, "k_small", k_small, "points; fine neighbourhood", Range::at_least(3, "covariance needs 3"));
//   }
//   void validate(const std::string& where) const { check_config(*this, where); }
//
// config_field() hands the range to visitors that take one (CheckVisitor below) and calls the
// plain three-argument form of every other visitor (apply_config, dump_config), so a config with
// ranges works with every helper of config.hpp unchanged.
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight {

/// Closed interval [min, max] of an arithmetic field; `why` (optional) is appended to the
/// message in parentheses. Floating-point fields with a range must also be finite.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  const char* why = "";

  static constexpr Range at_least(double lo, const char* why = "") {
    return {lo, std::numeric_limits<double>::infinity(), why};
  }
  static constexpr Range at_most(double hi, const char* why = "") {
    return {-std::numeric_limits<double>::infinity(), hi, why};
  }
  static constexpr Range within(double lo, double hi, const char* why = "") { return {lo, hi, why}; }

  /// "" when `value` is inside; else the rule it breaks: "must be at least 3 (why)".
  template <typename T>
  std::string violation(T value) const {
    const double v = static_cast<double>(value);
    std::string rule;
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(v)) rule = "must be finite";
    }
    if (rule.empty() && v < min) rule = "must be at least " + detail::format_value(min);
    if (rule.empty() && v > max) rule = "must be at most " + detail::format_value(max);
    if (!rule.empty() && why[0] != '\0') rule += std::string(" (") + why + ")";
    return rule;
  }
};

/// Declares one field with its range (see the top of this file).
template <class V, typename T>
void config_field(V& v, const char* name, T& field, const char* doc, const Range& range) {
  if constexpr (requires { v(name, field, doc, range); })
    v(name, field, doc, range);
  else
    v(name, field, doc);
}

namespace detail {
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
    static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, "a Range needs a numeric field");
    const std::string rule = range.violation(field);
    if (!rule.empty()) throw Error(where, "'" + prefix + name + "' " + rule + ", got " + format_value(field));
  }
};
}  // namespace detail

/// Throws Error(where, "'PREFIXkey' must be at least 3 (why), got 1") for the first field, in
/// declaration order (nested structs included), whose value is outside its declared Range.
template <typename Config>
void check_config(const Config& cfg, const std::string& where, const std::string& prefix = "") {
  detail::CheckVisitor v{where, prefix};
  const_cast<Config&>(cfg).visit(v);  // visit() only reads through CheckVisitor
}

}  // namespace cropsight
