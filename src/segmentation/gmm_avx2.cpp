// The GMM's EM compiled for AVX2 + FMA (8 float lanes, fused multiply-adds): ~2x the baseline
// SSE2 build's speed on the E- and M-step loops. Chosen at run time by fit_gmm() when the CPU
// has both; the x86-64 baseline build stays portable. See gmm_em.hpp and gmm_em_deps.hpp for
// why the includes come before the pragma.
#include "gmm_kernels.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include "gmm_em_deps.hpp"

#pragma GCC push_options
#pragma GCC target("avx2,fma")
#define CROPSIGHT_SIMD_LANES 8
#define CROPSIGHT_EM_NS em_avx2
#include "gmm_em.hpp"
#pragma GCC pop_options

namespace cropsight::segmentation::em_avx2 {
bool available() {
  static const bool ok = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return ok;
}
}  // namespace cropsight::segmentation::em_avx2

#else
#include "cropsight/core/error.hpp"

namespace cropsight::segmentation::em_avx2 {
bool available() { return false; }
GmmResult fit(const std::vector<Eigen::Vector3f>&, const GmmConfig&) {
  throw Error("gmm", "the AVX2 variant is not part of this build");
}
}  // namespace cropsight::segmentation::em_avx2
#endif
