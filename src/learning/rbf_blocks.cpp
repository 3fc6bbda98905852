// Form 3 of core/cpu_dispatch.hpp: this translation unit's kernel is compiled for AVX2 + FMA
// (helpers pass 8-lane vectors to each other); every header comes before the region.
#include "learning/rbf_blocks.hpp"

#include <cstdint>
#include <cstring>
#include <vector>

#include "core/cpu_dispatch.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::learning::detail {

RbfBlocks::RbfBlocks(const float* sv, int n, int cols, const float* coef, const float* norm2, float gamma)
    : cols_(cols), blocks_((n + kBlock - 1) / kBlock), gamma_(gamma) {
  const std::size_t w = kBlock;
  values_.assign(std::size_t(blocks_) * std::size_t(cols_) * w, 0.0f);
  coef_.assign(std::size_t(blocks_) * w, 0.0f);  // padding rows: coefficient 0 adds nothing
  norm2_.assign(std::size_t(blocks_) * w, 0.0f);
  for (int i = 0; i < n; ++i) {
    const std::size_t b = std::size_t(i / kBlock), l = std::size_t(i % kBlock);
    for (int j = 0; j < cols_; ++j)
      values_[(b * std::size_t(cols_) + std::size_t(j)) * w + l] =
          sv[std::size_t(i) * std::size_t(cols_) + std::size_t(j)];
    coef_[b * w + l] = coef[i];
    norm2_[b * w + l] = norm2[i];
  }
}

}  // namespace cropsight::learning::detail

#if CROPSIGHT_HAVE_AVX2_TU
CROPSIGHT_AVX2_FMA_BEGIN
namespace cropsight::learning::detail {
namespace {

typedef float v8f __attribute__((vector_size(32)));
typedef std::int32_t v8i __attribute__((vector_size(32)));

inline v8f splat(float x) { return v8f{x, x, x, x, x, x, x, x}; }
inline v8f load(const float* p) {
  v8f v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// exp(x) for x <= 0 (the kernel's arguments), eight lanes: x = n ln2 + r with |r| <= ln2 / 2
// (n rounded through the 1.5·2^23 shift), e^r by Cephes' expf polynomial, 2^n into the exponent
// bits. Below -87.3 (2^n would leave the normal range) the result is flushed to 0: such a term is
// under 1e-38 of its coefficient.
__attribute__((always_inline)) inline v8f exp_neg(v8f x) {
  const v8f lo = splat(-87.3f);
  const v8i underflow = x < lo;
  x = x < lo ? lo : x;
  const v8f shift = splat(12582912.0f);  // 1.5 · 2^23: adding it rounds to an integer
  const v8f t = x * splat(1.44269504088896341f) + shift;
  const v8f n = t - shift;
  v8f r = x - n * splat(0.693359375f);
  r = r - n * splat(-2.12194440e-4f);
  v8f p = splat(1.9875691500e-4f);
  p = p * r + splat(1.3981999507e-3f);
  p = p * r + splat(8.3334519073e-3f);
  p = p * r + splat(4.1665795894e-2f);
  p = p * r + splat(1.6666665459e-1f);
  p = p * r + splat(5.0000001201e-1f);
  p = p * (r * r) + r + splat(1.0f);
  v8i ti;
  std::memcpy(&ti, &t, sizeof ti);
  const v8i ni =
      ti - v8i{0x4B400000, 0x4B400000, 0x4B400000, 0x4B400000, 0x4B400000, 0x4B400000, 0x4B400000, 0x4B400000};
  const v8i bits = (ni + 127) << 23;
  v8f scale;
  std::memcpy(&scale, &bits, sizeof scale);
  const v8f e = p * scale;
  return underflow ? splat(0.0f) : e;
}

// Eight lanes of coef · exp(−γ · max(0, |sv|² + z2 − 2 dot)).
__attribute__((always_inline)) inline v8f terms(v8f dot, const float* norm2, const float* coef, float z2, float gamma) {
  v8f d2 = load(norm2) + splat(z2) - splat(2.0f) * dot;
  d2 = d2 > splat(0.0f) ? d2 : splat(0.0f);
  return load(coef) * exp_neg(splat(-gamma) * d2);
}

// Dot products of one or two vectors (rows of `cols` floats at z) with the 16 support vectors of
// block `p` (cols × 16 floats: two 8-lane halves per column). Per vector four chains (two halves ×
// even and odd columns) summed the same way in both functions, so a vector's bits do not depend
// on whether it was scored alone or beside another. Written out without arrays: the compiler
// kept arrays of accumulators on the stack.
__attribute__((always_inline)) inline void dots1(const float* p, int cols, const float* z, v8f& d0, v8f& d1) {
  v8f e0 = {}, e1 = {}, o0 = {}, o1 = {};
  int j = 0;
  for (; j + 1 < cols; j += 2) {
    const float* c = p + std::size_t(j) * 16;
    const v8f a = splat(z[j]), b = splat(z[j + 1]);
    e0 += load(c) * a, e1 += load(c + 8) * a;
    o0 += load(c + 16) * b, o1 += load(c + 24) * b;
  }
  if (j < cols) {
    const float* c = p + std::size_t(j) * 16;
    const v8f a = splat(z[j]);
    e0 += load(c) * a, e1 += load(c + 8) * a;
  }
  d0 = e0 + o0, d1 = e1 + o1;
}
__attribute__((always_inline)) inline void dots2(const float* p, int cols, const float* z, const float* y, v8f& d0,
                                                 v8f& d1, v8f& f0, v8f& f1) {
  v8f e0 = {}, e1 = {}, o0 = {}, o1 = {}, g0 = {}, g1 = {}, h0 = {}, h1 = {};
  int j = 0;
  for (; j + 1 < cols; j += 2) {
    const float* c = p + std::size_t(j) * 16;
    const v8f u0 = load(c), u1 = load(c + 8);
    const v8f a = splat(z[j]), x = splat(y[j]);
    e0 += u0 * a, e1 += u1 * a, g0 += u0 * x, g1 += u1 * x;
    const v8f w0 = load(c + 16), w1 = load(c + 24);
    const v8f b = splat(z[j + 1]), t = splat(y[j + 1]);
    o0 += w0 * b, o1 += w1 * b, h0 += w0 * t, h1 += w1 * t;
  }
  if (j < cols) {
    const float* c = p + std::size_t(j) * 16;
    const v8f u0 = load(c), u1 = load(c + 8);
    const v8f a = splat(z[j]), x = splat(y[j]);
    e0 += u0 * a, e1 += u1 * a, g0 += u0 * x, g1 += u1 * x;
  }
  d0 = e0 + o0, d1 = e1 + o1, f0 = g0 + h0, f1 = g1 + h1;
}

// acc (16 lanes) += the block's 16 terms for one vector.
__attribute__((always_inline)) inline void add_terms(float* acc, const float* norm2, const float* coef, float z2,
                                                     float gamma, v8f d0, v8f d1) {
  v8f a = load(acc), b = load(acc + 8);
  a += terms(d0, norm2, coef, z2, gamma);
  b += terms(d1, norm2 + 8, coef + 8, z2, gamma);
  std::memcpy(acc, &a, sizeof a);
  std::memcpy(acc + 8, &b, sizeof b);
}

// RbfBlocks::sums' body (the layout passed in pieces: no member access from inside the region).
// Per vector, 16 lane sums across blocks (in block order), then the lanes in order.
void block_sums(const float* values, const float* norm2, const float* coef, int blocks, int cols, float gamma,
                const float* z, const float* z2, std::size_t q, float* out, float* acc /* q × 16 */) {
  for (std::size_t i = 0; i < q * 16; ++i) acc[i] = 0.0f;
  constexpr int kGroup = 2;  // blocks per pass: 2 × 16 support vectors × up to 160 columns = 20 KB
  const std::size_t stride = std::size_t(cols) * 16;
  for (int g0 = 0; g0 < blocks; g0 += kGroup) {
    const int g1 = g0 + kGroup < blocks ? g0 + kGroup : blocks;
    std::size_t k = 0;
    for (; k + 2 <= q; k += 2) {
      const float* zk = z + k * std::size_t(cols);
      for (int b = g0; b < g1; ++b) {
        v8f d0, d1, f0, f1;
        dots2(values + std::size_t(b) * stride, cols, zk, zk + cols, d0, d1, f0, f1);
        const std::size_t at = std::size_t(b) * 16;
        add_terms(acc + k * 16, norm2 + at, coef + at, z2[k], gamma, d0, d1);
        add_terms(acc + (k + 1) * 16, norm2 + at, coef + at, z2[k + 1], gamma, f0, f1);
      }
    }
    for (; k < q; ++k) {
      const float* zk = z + k * std::size_t(cols);
      for (int b = g0; b < g1; ++b) {
        v8f d0, d1;
        dots1(values + std::size_t(b) * stride, cols, zk, d0, d1);
        const std::size_t at = std::size_t(b) * 16;
        add_terms(acc + k * 16, norm2 + at, coef + at, z2[k], gamma, d0, d1);
      }
    }
  }
  for (std::size_t k = 0; k < q; ++k) {
    float s = 0.0f;
    for (int l = 0; l < 16; ++l) s += acc[k * 16 + std::size_t(l)];
    out[k] = s;
  }
}

}  // namespace
}  // namespace cropsight::learning::detail
CROPSIGHT_AVX2_FMA_END

namespace cropsight::learning::detail {
bool RbfBlocks::available() { return cropsight::detail::cpu_has_avx2_fma(); }

void RbfBlocks::sums(const float* z, const float* z2, std::size_t q, float* out) const {
  if (!available()) throw Error("svm", "the AVX2 RBF kernel needs a CPU with AVX2 and FMA");
  if (q == 0) return;
  std::vector<float> acc(q * 16);
  block_sums(values_.data(), norm2_.data(), coef_.data(), blocks_, cols_, gamma_, z, z2, q, out, acc.data());
}
}  // namespace cropsight::learning::detail

#else
namespace cropsight::learning::detail {
bool RbfBlocks::available() { return false; }
void RbfBlocks::sums(const float*, const float*, std::size_t, float*) const {
  throw Error("svm", "the AVX2 RBF kernel is not part of this build");
}
}  // namespace cropsight::learning::detail
#endif
