#include "cropsight/features/feature_set.hpp"

#include <algorithm>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/features/viewpoint_angle.hpp"

namespace cropsight::features {

namespace {
struct KindInfo {
  FeatureSet::Kind kind;
  const char* name;
  int dim;
};
constexpr KindInfo kKinds[] = {{FeatureSet::Kind::Vfh, "vfh", kVfhBins},
                               {FeatureSet::Kind::ViewpointAngle, "va", kViewpointAngleBins},
                               {FeatureSet::Kind::Geometric, "geom", kGeometricFeatures},
                               {FeatureSet::Kind::Cvfh, "cvfh", kCvfhBins}};
const KindInfo& info(FeatureSet::Kind k) {
  for (const auto& i : kKinds)
    if (i.kind == k) return i;
  throw Error("features", "unknown feature kind");
}
}  // namespace

FeatureSet FeatureSet::parse(const std::string& spec, const std::string& where) {
  FeatureSet fs;
  std::stringstream in(spec);
  std::string item;
  while (std::getline(in, item, ',')) {
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    const KindInfo* found = nullptr;
    for (const auto& k : kKinds)
      if (item == k.name) found = &k;
    if (!found) throw Error(where, "unknown feature '" + item + "' (expected vfh, va, geom or cvfh)");
    if (std::find(fs.kinds_.begin(), fs.kinds_.end(), found->kind) != fs.kinds_.end())
      throw Error(where, "feature '" + item + "' is listed twice");
    fs.kinds_.push_back(found->kind);
  }
  if (fs.kinds_.empty()) throw Error(where, "empty feature list (expected e.g. 'vfh' or 'vfh,va,geom')");
  return fs;
}

std::string FeatureSet::spec() const {
  std::string s;
  for (Kind k : kinds_) s += (s.empty() ? "" : ",") + std::string(info(k).name);
  return s;
}

std::size_t FeatureSet::dimension() const {
  std::size_t d = 0;
  for (Kind k : kinds_) d += std::size_t(info(k).dim);
  return d;
}

std::vector<std::string> FeatureSet::names() const {
  std::vector<std::string> out;
  out.reserve(dimension());
  for (Kind k : kinds_) {
    const KindInfo& ki = info(k);
    if (k == Kind::Geometric) {
      for (const auto& g : geometric_feature_names()) out.push_back("geom_" + g);
    } else {
      for (int b = 0; b < ki.dim; ++b) out.push_back(std::string(ki.name) + "_" + std::to_string(b));
    }
  }
  return out;
}

void FeatureSet::compute(const OrganizedCloud& cloud, std::span<const int> indices, const FeatureConfig& cfg,
                         std::vector<float>& out) const {
  if (!cloud.has_normals() || cloud.nx.size() != cloud.size())
    throw Error("features", "the cloud has no normals (estimate them first)");
  for (int i : indices)
    if (i < 0 || std::size_t(i) >= cloud.size()) throw Error("features", "segment index out of the cloud");
  out.resize(dimension());
  float* p = out.data();
  for (Kind k : kinds_) {
    switch (k) {
      case Kind::Vfh:
        compute_vfh(cloud, indices, cfg.vfh, p);
        break;
      case Kind::ViewpointAngle:
        compute_viewpoint_angle_histogram(cloud, indices, p);
        break;
      case Kind::Geometric:
        compute_geometric_features(cloud, indices, geom_ws_, p);
        break;
      case Kind::Cvfh:
        compute_cvfh(cloud, indices, cfg.cvfh, p);
        break;
    }
    p += info(k).dim;
  }
}

}  // namespace cropsight::features
