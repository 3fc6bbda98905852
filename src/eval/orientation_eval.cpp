// eval/orientation_eval: errors modulo 180° and their grouping by light, angle and potato.
#include "cropsight/eval/orientation_eval.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

namespace cropsight::eval {

double axis_angle_error_deg(double truth_deg, double estimate_deg) {
  const double d = std::fmod(std::abs(truth_deg - estimate_deg), 180.0);
  return std::min(d, 180.0 - d);
}

namespace {

OrientationStats stats_of(const std::string& key, const std::vector<double>& errors, int failures) {
  OrientationStats s;
  s.key = key;
  s.count = int(errors.size());
  s.failures = failures;
  if (errors.empty()) return s;
  double sum = 0, sq = 0;
  for (double e : errors) sum += e, s.max_deg = std::max(s.max_deg, e);
  s.mae_deg = sum / double(errors.size());
  for (double e : errors) sq += (e - s.mae_deg) * (e - s.mae_deg);
  s.std_deg = std::sqrt(sq / double(errors.size()));
  return s;
}

std::vector<OrientationStats> grouped(const std::vector<OrientationSample>& samples, const std::vector<double>& errors,
                                      const std::function<std::string(const OrientationSample&)>& key_of,
                                      bool numeric) {
  std::map<std::string, std::pair<std::vector<double>, int>> groups;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    auto& g = groups[key_of(samples[i])];
    g.first.push_back(errors[i]);
    g.second += samples[i].ok ? 0 : 1;
  }
  std::vector<OrientationStats> out;
  for (const auto& [k, g] : groups) out.push_back(stats_of(k, g.first, g.second));
  if (numeric)
    std::sort(out.begin(), out.end(),
              [](const OrientationStats& a, const OrientationStats& b) { return std::stod(a.key) < std::stod(b.key); });
  return out;
}

std::string angle_key(double deg) {
  const double r = std::round(deg);
  return std::abs(deg - r) < 1e-9 ? std::to_string(int(r)) : std::to_string(deg);
}

}  // namespace

OrientationEvaluation summarise_orientation(std::vector<OrientationSample> samples) {
  OrientationEvaluation e;
  e.samples = std::move(samples);
  int failures = 0;
  double ms = 0;
  for (const auto& s : e.samples) {
    e.errors_deg.push_back(s.ok ? axis_angle_error_deg(s.truth_deg, s.estimate_deg) : 90.0);
    failures += s.ok ? 0 : 1;
    ms += s.ms;
  }
  e.all = stats_of("all", e.errors_deg, failures);
  e.ms_per_potato = e.samples.empty() ? 0 : ms / double(e.samples.size());
  e.per_light = grouped(
      e.samples, e.errors_deg, [](const OrientationSample& s) { return s.light; }, false);
  e.per_angle = grouped(
      e.samples, e.errors_deg, [](const OrientationSample& s) { return angle_key(s.truth_deg); }, true);
  e.per_potato = grouped(
      e.samples, e.errors_deg, [](const OrientationSample& s) { return std::to_string(s.potato); }, true);
  return e;
}

}  // namespace cropsight::eval
