#include "geometry/farthest_point_step.hpp"

#include <cmath>

#include "core/cpu_dispatch.hpp"

#if CROPSIGHT_X86_DISPATCH
#include <immintrin.h>
#endif

namespace cropsight::geometry::detail {

namespace {

// std::min(old, d) as the original loop wrote it: d when d < old, else old (a NaN distance keeps
// the old value, as _mm256_min_ps(d, old) does).
inline float lower(float old, float d) { return d < old ? d : old; }

inline float distance(float dx, float dy, float dz) { return std::sqrt(dx * dx + (dy * dy + dz * dz)); }

float update_baseline(const float* x, const float* y, const float* z, float* dist, std::size_t b, std::size_t n,
                      float cx, float cy, float cz, float best) {
  for (std::size_t i = b; i < n; ++i) {
    const float v = lower(dist[i], distance(x[i] - cx, y[i] - cy, z[i] - cz));
    dist[i] = v;
    best = v > best ? v : best;
  }
  return best;
}

std::size_t first_equal(const float* dist, std::size_t b, std::size_t n, float best) {
  for (std::size_t i = b; i < n; ++i)
    if (dist[i] == best) return i;
  return n;
}

#if CROPSIGHT_X86_DISPATCH
// Eight points a step: the same subtractions, products, sums (dy² + dz² first) and correctly
// rounded square root as the baseline loop, lane by lane (no FMA in this target).
CROPSIGHT_TARGET_AVX2 std::size_t step_avx2(const float* x, const float* y, const float* z, float* dist, std::size_t n,
                                            float cx, float cy, float cz) {
  const __m256 vx = _mm256_set1_ps(cx), vy = _mm256_set1_ps(cy), vz = _mm256_set1_ps(cz);
  __m256 vbest = _mm256_set1_ps(-2.f);
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(x + i), vx);
    const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(y + i), vy);
    const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(z + i), vz);
    const __m256 d = _mm256_sqrt_ps(
        _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_add_ps(_mm256_mul_ps(dy, dy), _mm256_mul_ps(dz, dz))));
    const __m256 v = _mm256_min_ps(d, _mm256_loadu_ps(dist + i));  // d < old ? d : old
    _mm256_storeu_ps(dist + i, v);
    vbest = _mm256_max_ps(v, vbest);  // v > best ? v : best
  }
  alignas(32) float lanes[8];
  _mm256_store_ps(lanes, vbest);
  float best = update_baseline(x, y, z, dist, i, n, cx, cy, cz, -2.f);
  for (float l : lanes) best = l > best ? l : best;
  // The first index holding the largest value, eight comparisons at a time.
  const __m256 target = _mm256_set1_ps(best);
  std::size_t j = 0;
  for (; j + 8 <= n; j += 8) {
    const int mask = _mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(dist + j), target, _CMP_EQ_OQ));
    if (mask) return j + std::size_t(__builtin_ctz(unsigned(mask)));
  }
  return first_equal(dist, j, n, best);
}
#endif

}  // namespace

std::size_t farthest_point_step(const float* x, const float* y, const float* z, float* dist, std::size_t n, float cx,
                                float cy, float cz, bool allow_avx2) {
#if CROPSIGHT_X86_DISPATCH
  if (allow_avx2 && cropsight::detail::cpu_has_avx2_fma()) return step_avx2(x, y, z, dist, n, cx, cy, cz);
#else
  (void)allow_avx2;
#endif
  const float best = update_baseline(x, y, z, dist, 0, n, cx, cy, cz, -2.f);
  return first_equal(dist, 0, n, best);
}

}  // namespace cropsight::geometry::detail
