// The GMM's EM compiled for AVX2 + FMA (8 float lanes, fused multiply-adds): ~2x the baseline
// SSE2 build's speed on the E- and M-step loops. Chosen at run time by fit_gmm() when
// cpu_has_avx2_fma(); the x86-64 baseline build stays portable. This is form 3 of
// core/cpu_dispatch.hpp (a whole translation unit under CROPSIGHT_AVX2_FMA_BEGIN / _END); see
// there, gmm_em.hpp and gmm_em_deps.hpp for why the includes come before the region.
#include "core/cpu_dispatch.hpp"
#include "gmm_kernels.hpp"

#if CROPSIGHT_HAVE_AVX2_TU
#include "gmm_em_deps.hpp"

CROPSIGHT_AVX2_FMA_BEGIN
#define CROPSIGHT_SIMD_LANES 8
#define CROPSIGHT_EM_NS em_avx2
#include "gmm_em.hpp"
CROPSIGHT_AVX2_FMA_END

namespace cropsight::segmentation::em_avx2 {
bool available() { return cropsight::detail::cpu_has_avx2_fma(); }
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
