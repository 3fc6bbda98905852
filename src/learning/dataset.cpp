#include "cropsight/learning/dataset.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"

namespace cropsight::learning {

void Dataset::add(std::span<const float> x, int label, const std::string& where) {
  if (dim == 0 && empty()) dim = int(x.size());
  if (int(x.size()) != dim)
    throw Error(where, "feature vector has " + std::to_string(x.size()) + " values, expected " + std::to_string(dim));
  if (label != 0 && label != 1) throw Error(where, "label must be 0 or 1, got " + std::to_string(label));
  for (float v : x)
    if (!std::isfinite(v)) throw Error(where, "feature vector has a non-finite value");
  values.insert(values.end(), x.begin(), x.end());
  labels.push_back(label);
}

void Dataset::append(const Dataset& other, const std::string& where) {
  if (other.empty()) return;
  if (empty() && dim == 0) dim = other.dim;
  if (other.dim != dim)
    throw Error(where,
                "cannot merge datasets of dimension " + std::to_string(dim) + " and " + std::to_string(other.dim));
  values.insert(values.end(), other.values.begin(), other.values.end());
  labels.insert(labels.end(), other.labels.begin(), other.labels.end());
}

std::size_t Dataset::positives() const { return std::size_t(std::count(labels.begin(), labels.end(), 1)); }

Dataset Dataset::subset(std::span<const std::size_t> idx) const {
  Dataset out(dim);
  out.values.reserve(idx.size() * std::size_t(dim));
  out.labels.reserve(idx.size());
  for (std::size_t i : idx) {
    out.values.insert(out.values.end(), row(i), row(i) + dim);
    out.labels.push_back(labels[i]);
  }
  return out;
}

}  // namespace cropsight::learning
