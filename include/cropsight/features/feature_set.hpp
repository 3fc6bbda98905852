#pragma once
// A named, ordered set of per-segment features, concatenated into one float vector with a stable
// dimension and stable element names (recorded in model files so that a model is only used with
// the features it was trained on).
//
// Spec: comma-separated kinds, each at most once, order kept: "vfh" (308), "va" (viewpoint-angle
// histogram, 12), "geom" (geometric features, 5), "cvfh" (308). Example "vfh,va,geom".
// Element names: "vfh_0".."vfh_307", "va_0".."va_11", "geom_area", "geom_compactness",
// "geom_smoothness", "geom_convexity", "geom_symmetry", "cvfh_0".."cvfh_307".
#include <span>
#include <string>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"
#include "cropsight/features/cvfh.hpp"
#include "cropsight/features/geometric.hpp"
#include "cropsight/features/vfh.hpp"

namespace cropsight::features {

struct FeatureConfig {
  VfhConfig vfh;
  CvfhConfig cvfh;

  template <class V>
  void visit(V& v) {
    v("vfh", vfh, "VFH options");
    v("cvfh", cvfh, "CVFH options");
  }
};

class FeatureSet {
 public:
  enum class Kind { Vfh, ViewpointAngle, Geometric, Cvfh };

  /// Parses a spec; throws Error(where, ...) for an empty spec, an unknown or repeated kind.
  static FeatureSet parse(const std::string& spec, const std::string& where = "features");

  FeatureSet() = default;
  const std::vector<Kind>& kinds() const { return kinds_; }
  std::string spec() const;                               ///< canonical text, e.g. "vfh,va"
  std::size_t dimension() const;                          ///< total floats per segment
  std::vector<std::string> names() const;                 ///< one per element
  bool needs_normals() const { return !kinds_.empty(); }  ///< every kind uses normals

  /// Computes the concatenated features of `indices` into `out` (resized to dimension()).
  /// Requires cloud.has_normals(); throws Error("features", ...) otherwise.
  void compute(const OrganizedCloud& cloud, std::span<const int> indices, const FeatureConfig& cfg,
               std::vector<float>& out) const;
  void compute(const OrganizedCloud& cloud, const Segment& seg, const FeatureConfig& cfg,
               std::vector<float>& out) const {
    compute(cloud, seg.indices, cfg, out);
  }

 private:
  std::vector<Kind> kinds_;
  mutable GeometricWorkspace geom_ws_;  // buffer reuse only; makes compute() not thread-safe
};

}  // namespace cropsight::features
