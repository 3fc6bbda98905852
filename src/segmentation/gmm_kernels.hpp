#pragma once
// Internal: the instruction-set variants of the GMM's EM, for fit_gmm()'s run-time dispatch and
// for the test that checks the variants against each other. Inputs must already be checked
// (finite points, at least cfg.components of them, cfg.components >= 1).
#include <Eigen/Core>
#include <vector>

#include "cropsight/segmentation/gmm.hpp"

namespace cropsight::segmentation {
namespace em_portable {
GmmResult fit(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg);  // SSE2 (x86-64 baseline)
GmmModel initial(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg);
}  // namespace em_portable
namespace em_avx2 {
/// True when this build has the AVX2 + FMA variant and the CPU runs it (cpu_has_avx2_fma()).
bool available();
GmmResult fit(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg);  // call only when available()
}  // namespace em_avx2
}  // namespace cropsight::segmentation
