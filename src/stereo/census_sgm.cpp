#include "census_sgm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "core/cpu_dispatch.hpp"
#include "core/parallel_for.hpp"
#include "cropsight/core/error.hpp"

#if CROPSIGHT_X86_DISPATCH
#include <immintrin.h>
#endif

// 32-byte vectors are passed between always-inlined helpers only; the ABI note GCC emits for
// them in the SSE2 build does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace cropsight::stereo::detail {
namespace {

using i16 = std::int16_t;
using v16 = i16 __attribute__((vector_size(32)));  // 16 disparities
using v16u32 = std::uint32_t __attribute__((vector_size(64)));
constexpr int kLanes = 16;
constexpr i16 kBig = 0x3FFF;  // sentinel / "no value"; kBig + p1 and 5 * (62 + p2) fit in int16
constexpr int kOff = 16;      // data offset of one disparity run inside a padded buffer
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

#define CS_INLINE inline __attribute__((always_inline))

CS_INLINE v16 ld(const i16* p) {
  v16 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
CS_INLINE void st(i16* p, v16 v) { std::memcpy(p, &v, sizeof v); }
CS_INLINE v16 vmin(v16 a, v16 b) { return a < b ? a : b; }
CS_INLINE v16 splat(int x) { return v16{} + i16(x); }
// Smallest of the 16 lanes (every value the kernel reduces lies in [0, kBig]). The AVX2 kernel
// folds the halves and lets SSE4.1's phminposuw find the minimum of 8 (an extract, a min and
// phminposuw instead of four shuffle / min pairs, on the chain that carries the horizontal path
// from pixel to pixel); the builtin is expanded inside sweep_band_avx2, whose target includes SSE4.1.
template <bool kAvx2>
CS_INLINE i16 hmin(v16 v) {
#if CROPSIGHT_X86_DISPATCH && !defined(__clang__)
  if constexpr (kAvx2) {
    using v8 = i16 __attribute__((vector_size(16)));
    const v8 lo = __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7);
    const v8 hi = __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15);
    return __builtin_ia32_phminposuw128(lo < hi ? lo : hi)[0];
  }
#endif
  v = vmin(v, __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3, 4, 5, 6, 7));
  v = vmin(v, __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11));
  v = vmin(v, __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5, 10, 11, 8, 9, 14, 15, 12, 13));
  v = vmin(v, __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14));
  return v[0];
}

// One SGM step for 16 disparities: L(d) = C(d) + min(Lp(d), Lp(d±1) + P1, min Lp + P2) - min Lp.
// `src` points at Lp(d0) inside a buffer with kBig sentinels before d = 0 and after d = D-1.
CS_INLINE v16 sgm_step(const i16* src, v16 c, v16 p1, v16 mp_p2, v16 mp) {
  const v16 t = vmin(ld(src), vmin(ld(src - 1), ld(src + 1)) + p1);
  return c + vmin(t, mp_p2) - mp;
}

// Bits set in v: the popcnt instruction where the kernel is compiled for it, else the SWAR sum
// (a libgcc call per cost would dominate the portable kernel).
template <bool kPopcnt>
CS_INLINE int popcount(std::uint64_t v) {
  if constexpr (kPopcnt) {
    return __builtin_popcountll(v);
  } else {
    v = v - ((v >> 1) & 0x5555555555555555ULL);
    v = (v & 0x3333333333333333ULL) + ((v >> 2) & 0x3333333333333333ULL);
    v = (v + (v >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
    return int((v * 0x0101010101010101ULL) >> 56);
  }
}

#if CROPSIGHT_X86_DISPATCH
// Bits per 16-bit half of each 32-bit word of v: per-byte popcount by nibble table look-up
// (vpshufb), byte pairs summed by vpmaddubsw.
CROPSIGHT_TARGET_AVX2 CS_INLINE __m256i popcount_halves_avx2(__m256i v) {
  const __m256i nibble = _mm256_set1_epi8(0x0F), ones = _mm256_set1_epi8(1);
  const __m256i table = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4,  //
                                         0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4);
  const __m256i lo = _mm256_and_si256(v, nibble), hi = _mm256_and_si256(_mm256_srli_epi16(v, 4), nibble);
  return _mm256_maddubs_epi16(_mm256_add_epi8(_mm256_shuffle_epi8(table, lo), _mm256_shuffle_epi8(table, hi)), ones);
}

// Matching costs of one row for census words of at most 32 bits: cost[x * D + d] = Hamming
// distance between left word x and mirrored right word W - 1 - x + d (x - d in the right image).
// The AVX2 table look-up takes about half the instructions of the portable SWAR count in 32-bit
// lanes, the largest single block of the matcher in a perf profile; both give the exact count. Not inlined:
// one call per row, and a target-specific body.
CROPSIGHT_TARGET_AVX2 void cost_row32_avx2(const std::uint64_t* cl, const std::uint32_t* crev, int W, int D,
                                           i16* cost) {
  for (int x = 0; x < W; ++x) {
    const __m256i av = _mm256_set1_epi32(int(std::uint32_t(cl[x])));
    const std::uint32_t* rr = crev + (W - 1 - x);
    for (int o = 0; o < D; o += kLanes) {
      const __m256i h0 = popcount_halves_avx2(_mm256_xor_si256(_mm256_loadu_si256((const __m256i*)(rr + o)), av));
      const __m256i h1 = popcount_halves_avx2(_mm256_xor_si256(_mm256_loadu_si256((const __m256i*)(rr + o + 8)), av));
      // hadd within 128-bit halves gives words 0-3, 8-11 | 4-7, 12-15; the permute restores 0..15.
      const __m256i sum = _mm256_permute4x64_epi64(_mm256_hadd_epi16(h0, h1), 0xD8);
      _mm256_storeu_si256((__m256i*)(cost + std::size_t(x) * std::size_t(D) + std::size_t(o)), sum);
    }
  }
}
#endif

void cost_row32_portable(const std::uint64_t* cl, const std::uint32_t* crev, int W, int D, i16* cost) {
  for (int x = 0; x < W; ++x) {
    const v16u32 a = v16u32{} + std::uint32_t(cl[x]);
    const std::uint32_t* rr = crev + (W - 1 - x);
    for (int o = 0; o < D; o += kLanes) {
      v16u32 v;
      std::memcpy(&v, rr + o, sizeof v);
      v ^= a;
      v = v - ((v >> 1) & 0x55555555u);
      v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
      v = (v + (v >> 4)) & 0x0F0F0F0Fu;
      v = (v + (v >> 8) + (v >> 16) + (v >> 24)) & 0x3Fu;
      st(cost + std::size_t(x) * std::size_t(D) + std::size_t(o), __builtin_convertvector(v, v16));
    }
  }
}

#if !CROPSIGHT_X86_DISPATCH
void cost_row32_avx2(const std::uint64_t* cl, const std::uint32_t* crev, int W, int D, i16* cost) {
  cost_row32_portable(cl, crev, W, D, cost);
}
#endif

struct Geometry {
  int W, H, D, rx, ry, bits;
};

using v32u8 = std::uint8_t __attribute__((vector_size(32)));

// Census of one row: bit k of pixel x is set when the k-th window neighbour is darker than the
// centre. Bits are gathered into 8 byte planes with 32-pixel vector compares, then the planes
// are interleaved into the 64-bit words; the bit order is irrelevant for Hamming costs.
// `planes` holds 8 rows of `stride` >= W + 32 bytes.
CS_INLINE void census_row(const cv::Mat& pad, int y, const Geometry& g, std::uint8_t* planes, int stride,
                          std::uint64_t* __restrict out) {
  const int W = g.W, vecW = W / 32 * 32;
  std::memset(planes, 0, std::size_t(stride) * 8);
  const std::uint8_t* c = pad.ptr<std::uint8_t>(y + g.ry) + g.rx;
  int k = 0;
  for (int dy = -g.ry; dy <= g.ry; ++dy)
    for (int dx = -g.rx; dx <= g.rx; ++dx) {
      if (dy == 0 && dx == 0) continue;
      const std::uint8_t* n = pad.ptr<std::uint8_t>(y + g.ry + dy) + g.rx + dx;
      std::uint8_t* acc = planes + std::size_t(k >> 3) * std::size_t(stride);
      const std::uint8_t bit = std::uint8_t(1u << (k & 7));
      int x = 0;
      for (; x < vecW; x += 32) {
        v32u8 a, nv, cv;
        std::memcpy(&a, acc + x, 32);
        std::memcpy(&nv, n + x, 32);
        std::memcpy(&cv, c + x, 32);
        a |= (v32u8)(nv < cv) & bit;
        std::memcpy(acc + x, &a, 32);
      }
      for (; x < W; ++x) acc[x] = std::uint8_t(acc[x] | (n[x] < c[x] ? bit : 0));
      ++k;
    }
  const std::uint8_t* __restrict p0 = planes;
  for (int x = 0; x < W; ++x) {
    std::uint64_t v = 0;
    for (int b = 0; b < 8; ++b)
      v |= std::uint64_t(p0[std::size_t(b) * std::size_t(stride) + std::size_t(x)]) << (8 * b);
    out[x] = v;
  }
}

struct BandJob {
  const cv::Mat* pad_left;
  const cv::Mat* pad_right;
  Geometry g;
  int p1, p2, uniqueness, lr_check, outside_cost, box;
  const int* p2_of_step;      // [256]: P2 for a grey-level step |I(p) - I(p - r)| along the path
  int first_row, rows, step;  // rows first_row, first_row + step, ... (step = +1 or -1)
  DisparityImage* out;
};

// One sweep over a band of rows: 5 SGM paths (left->right, right->left, and the vertical and two
// diagonal ones coming from the previous row of the sweep), then winner-take-all, right-view
// winner along the diagonals, left-right check and sub-pixel fit per row.
// Long on purpose: the matcher's hot loop; the five paths and the per-row steps share the band's
// cost and path buffers row by row, which one body keeps in registers and cache.
template <bool kPopcnt>
CS_INLINE void sweep_band_impl(const BandJob& job) {
  const Geometry& g = job.g;
  const int W = g.W, D = g.D, NB = D / kLanes, P = D + 2 * kOff;
  const std::size_t WP = std::size_t(W) * std::size_t(P);
  // Path buffers: previous / current row for the three inter-row paths, previous / current
  // pixel for the two horizontal ones; every disparity run has kBig sentinels around it.
  std::vector<i16> rowbuf(6 * WP, kBig), hbuf(5 * std::size_t(P), kBig);
  i16* Lv[2] = {rowbuf.data(), rowbuf.data() + WP};               // from (x, y-1)
  i16* La[2] = {rowbuf.data() + 2 * WP, rowbuf.data() + 3 * WP};  // from (x-1, y-1)
  i16* Lb[2] = {rowbuf.data() + 4 * WP, rowbuf.data() + 5 * WP};  // from (x+1, y-1)
  i16* Lh[2] = {hbuf.data(), hbuf.data() + P};
  i16* zero = hbuf.data() + 4 * P;  // a path start: Lp = 0, min Lp = 0 gives L = C
  std::fill(zero + kOff, zero + kOff + D, i16(0));
  for (i16* buf : {Lv[1], La[1], Lb[1]})  // row 0 reads slot 1 as its previous row
    for (int x = 0; x < W; ++x) std::fill(buf + std::size_t(x) * P + kOff, buf + std::size_t(x) * P + kOff + D, 0);
  std::vector<i16> mins(6 * std::size_t(W), 0);
  i16* mv[2] = {mins.data(), mins.data() + W};
  i16* ma[2] = {mins.data() + 2 * W, mins.data() + 3 * W};
  i16* mb[2] = {mins.data() + 4 * W, mins.data() + 5 * W};

  std::vector<i16> cost(std::size_t(W) * D), sum(std::size_t(W) * D);
  std::vector<i16> boxsrc(job.box > 1 ? std::size_t(W + job.box) * D : 0);
  std::vector<i16> rmin(std::size_t(W + D + kLanes)), rarg(std::size_t(W + D + kLanes));
  const auto w = std::size_t(W);
  std::vector<std::uint64_t> cl(w), cr(w);
  std::vector<std::uint32_t> crev(w + std::size_t(D) + kLanes, 0);  // mirrored right census, <= 32 bits
  const int pstride = (W + 63) / 32 * 32;
  std::vector<std::uint8_t> planes(std::size_t(pstride) * 8);
  std::vector<int> best(w);
  std::vector<float> sub(w);

  const v16 p1 = splat(job.p1), iota = v16{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  const v16 big = splat(kBig);

  for (int r = 0; r < job.rows; ++r) {
    const int y = job.first_row + r * job.step;
    const int cur = r & 1, prev = cur ^ 1;
    // Matching costs of the row. A disparity that puts the partner left of the right image, or
    // so close to its border that the census window is cut (replicated pixels), gets the cost of
    // an unrelated pair (half the census bits): it neither wins by chance nor bends the sub-pixel
    // fit of its neighbours; matches landing there are rejected below.
    census_row(*job.pad_left, y, g, planes.data(), pstride, cl.data());
    census_row(*job.pad_right, y, g, planes.data(), pstride, cr.data());
    if (g.bits <= 32) {
      // Up to 32 census bits: 16 disparities at a time (cost_row32_*), on the right census stored
      // mirrored so that x - d for d = d0..d0+15 is 16 consecutive words.
      for (int x = 0; x < W; ++x) crev[std::size_t(W - 1 - x)] = std::uint32_t(cr[std::size_t(x)]);
      const v16 outside = splat(job.outside_cost);
      (kPopcnt ? cost_row32_avx2 : cost_row32_portable)(cl.data(), crev.data(), W, D, cost.data());
      for (int x = 0; x < W && x - g.rx < D - 1; ++x) {
        i16* c = cost.data() + std::size_t(x) * D;
        // Left of x = rx + D - 1 some disparities point outside the right image's full windows.
        const v16 dmax = splat(x - g.rx);
        for (int o = 0; o < D; o += kLanes) st(c + o, (iota + i16(o)) > dmax ? outside : ld(c + o));
      }
    } else {
      for (int x = 0; x < W; ++x) {
        const std::uint64_t a = cl[std::size_t(x)];
        const std::uint64_t* rr = cr.data() + x;
        i16* c = cost.data() + std::size_t(x) * D;
        const int dmax = std::min(x - g.rx, D - 1);
        for (int d = 0; d <= dmax; ++d) c[d] = i16(popcount<kPopcnt>(a ^ rr[-d]));
        for (int d = std::max(dmax + 1, 0); d < D; ++d) c[d] = i16(job.outside_cost);
      }
    }

    if (job.box > 1) {
      // Horizontal box sum of the costs over `box` columns (same disparity): more support on
      // low-contrast texture, like SGBM's block window. Border columns repeat the edge cost.
      const int h = job.box / 2;
      for (int x = 0; x < W; ++x)
        std::memcpy(boxsrc.data() + std::size_t(x + h) * D, cost.data() + std::size_t(x) * D,
                    sizeof(i16) * std::size_t(D));
      for (int k = 0; k < h; ++k) {
        std::memcpy(boxsrc.data() + std::size_t(k) * D, cost.data(), sizeof(i16) * std::size_t(D));
        std::memcpy(boxsrc.data() + std::size_t(W + h + k) * D, cost.data() + std::size_t(W - 1) * D,
                    sizeof(i16) * std::size_t(D));
      }
      for (int x = 0; x < W; ++x)
        for (int o = 0; o < D; o += kLanes) {
          v16 acc = v16{};
          for (int k = 0; k < job.box; ++k) acc += ld(boxsrc.data() + std::size_t(x + k) * D + o);
          st(cost.data() + std::size_t(x) * D + o, acc);
        }
    }
    const std::uint8_t* Ic = job.pad_left->ptr<std::uint8_t>(y + g.ry) + g.rx;
    const std::uint8_t* Ip = r > 0 ? job.pad_left->ptr<std::uint8_t>(y - job.step + g.ry) + g.rx : Ic;
    // Forward pass: the three inter-row paths and left->right; their sum starts S.
    for (int x = 0; x < W; ++x) {
      const i16* C = cost.data() + std::size_t(x) * D;
      i16* S = sum.data() + std::size_t(x) * D;
      const i16* sv = Lv[prev] + std::size_t(x) * P + kOff;
      const i16* sa = x > 0 ? La[prev] + std::size_t(x - 1) * P + kOff : zero + kOff;
      const i16* sb = x + 1 < W ? Lb[prev] + std::size_t(x + 1) * P + kOff : zero + kOff;
      const i16* sh = x > 0 ? Lh[(x - 1) & 1] + kOff : zero + kOff;
      const int mpv = mv[prev][x], mpa = x > 0 ? ma[prev][x - 1] : 0, mpb = x + 1 < W ? mb[prev][x + 1] : 0;
      const int mph = x > 0 ? Lh[(x - 1) & 1][0] : 0;  // the run's minimum is kept in slot 0
      i16* dv = Lv[cur] + std::size_t(x) * P + kOff;
      i16* da = La[cur] + std::size_t(x) * P + kOff;
      i16* db = Lb[cur] + std::size_t(x) * P + kOff;
      i16* dh = Lh[x & 1] + kOff;
      const v16 vv = splat(mpv), va = splat(mpa), vb = splat(mpb), vh = splat(mph);
      const int* q2 = job.p2_of_step;
      const int ic = Ic[x], xl = std::max(x - 1, 0), xn = std::min(x + 1, W - 1);
      const v16 vv2 = splat(mpv + q2[std::abs(ic - Ip[x])]), va2 = splat(mpa + q2[std::abs(ic - Ip[xl])]),
                vb2 = splat(mpb + q2[std::abs(ic - Ip[xn])]), vh2 = splat(mph + q2[std::abs(ic - Ic[xl])]);
      v16 nv = big, na = big, nb = big, nh = big;
      for (int b = 0; b < NB; ++b) {
        const int o = b * kLanes;
        const v16 c = ld(C + o);
        const v16 lv = sgm_step(sv + o, c, p1, vv2, vv), la = sgm_step(sa + o, c, p1, va2, va),
                  lb = sgm_step(sb + o, c, p1, vb2, vb), lh = sgm_step(sh + o, c, p1, vh2, vh);
        st(dv + o, lv), st(da + o, la), st(db + o, lb), st(dh + o, lh);
        nv = vmin(nv, lv), na = vmin(na, la), nb = vmin(nb, lb), nh = vmin(nh, lh);
        st(S + o, lv + la + lb + lh);
      }
      mv[cur][x] = hmin<kPopcnt>(nv), ma[cur][x] = hmin<kPopcnt>(na), mb[cur][x] = hmin<kPopcnt>(nb);
      Lh[x & 1][0] = hmin<kPopcnt>(nh);  // slot 0 lies outside the data run and its sentinel
    }

    // Backward pass: right->left completes S; winner-take-all for the left view and running
    // minima along the diagonals for the right view (right pixel xr = x - d, stored at
    // W - 1 - xr so that 16 consecutive disparities are 16 consecutive slots).
    std::fill(rmin.begin(), rmin.end(), kBig);
    std::fill(rarg.begin(), rarg.end(), i16(0));
    for (int x = W - 1; x >= 0; --x) {
      const i16* C = cost.data() + std::size_t(x) * D;
      i16* S = sum.data() + std::size_t(x) * D;
      const bool start = x == W - 1;
      const i16* sh = start ? zero + kOff : Lh[(x + 1) & 1] + kOff;
      const int mph = start ? 0 : Lh[(x + 1) & 1][0];
      i16* dh = Lh[x & 1] + kOff;
      const v16 vh = splat(mph), vh2 = splat(mph + job.p2_of_step[std::abs(Ic[x] - Ic[std::min(x + 1, W - 1)])]);
      // Per lane (disparities d = lane mod 16): the best sum, its disparity and the best of the
      // lane's other disparities, which are all >= 16 away from the lane's best.
      v16 nh = big, bestv = big, besti = v16{}, second = big;
      i16* rm = rmin.data() + (W - 1 - x);
      i16* ra = rarg.data() + (W - 1 - x);
      for (int b = 0; b < NB; ++b) {
        const int o = b * kLanes;
        const v16 lh = sgm_step(sh + o, ld(C + o), p1, vh2, vh);
        st(dh + o, lh);
        nh = vmin(nh, lh);
        const v16 s = ld(S + o) + lh;
        st(S + o, s);
        const v16 dvec = iota + i16(o);
        const v16 better = s < bestv;
        second = better ? bestv : vmin(second, s);
        bestv = better ? s : bestv;
        besti = better ? dvec : besti;
        const v16 m = ld(rm + o), rbetter = s < m;
        st(rm + o, rbetter ? s : m);
        st(ra + o, rbetter ? dvec : ld(ra + o));
      }
      Lh[x & 1][0] = hmin<kPopcnt>(nh);
      const i16 smin = hmin<kPopcnt>(bestv);
      const int bd = hmin<kPopcnt>(bestv == smin ? besti : big);  // smallest disparity among ties
      // Uniqueness (OpenCV's rule): no disparity more than 1 px away may come within
      // uniqueness% of the best cost. The smallest sum over |d - bd| > 1 is, per lane, the lane's
      // best unless that lies within 1 px of bd (then the lane's runner-up): no second pass.
      bool ok = true;
      if (job.uniqueness > 0) {
        const v16 dd = besti - splat(bd);
        const v16 near = (dd >= -1) & (dd <= 1);
        const v16 others = near ? second : bestv;
        ok = int(hmin<kPopcnt>(others)) * (100 - job.uniqueness) >= int(smin) * 100;
      }
      best[std::size_t(x)] = ok ? bd : -1;
      float f = float(bd);
      if (bd > 0 && bd < std::min(x - g.rx, D - 1)) {  // both neighbours are real matching costs
        const int a = S[bd - 1], c = S[bd + 1], den = a + c - 2 * int(smin);
        if (den > 0) f += float(a - c) / float(2 * den);
      }
      sub[std::size_t(x)] = f;
    }

    float* outrow = job.out->row(y);
    const int xr_min = g.rx + 1 + std::max(job.lr_check, 0);
    for (int x = 0; x < W; ++x) {
      const int d = best[std::size_t(x)];
      const int xr = x - d;
      // No match left of the right image's full census windows, nor within the LR tolerance of
      // that zone: there a pixel whose true partner is cut off can pass the check with a
      // neighbouring disparity.
      bool ok = d >= 0 && xr >= xr_min;
      if (ok && job.lr_check >= 0) ok = std::abs(int(rarg[std::size_t(W - 1 - xr)]) - d) <= job.lr_check;
      outrow[x] = ok ? sub[std::size_t(x)] : kNaN;
    }
  }
}

CROPSIGHT_TARGET_AVX2 void sweep_band_avx2(const BandJob& job) { sweep_band_impl<true>(job); }
void sweep_band_portable(const BandJob& job) { sweep_band_impl<false>(job); }

}  // namespace

DisparityImage census_sgm(const cv::Mat& left, const cv::Mat& right, const CensusSgmParams& p) {
  const std::string where = "census SGM";
  if (left.type() != CV_8UC1 || right.type() != CV_8UC1) throw Error(where, "expects 8-bit single-channel images");
  if (left.size() != right.size() || left.empty()) throw Error(where, "images must be non-empty and of equal size");
  if (p.num_disparities <= 0 || p.num_disparities % kLanes != 0)
    throw Error(where, "num_disparities must be a positive multiple of 16");
  if (p.census_width < 1 || p.census_height < 1 || p.census_width % 2 == 0 || p.census_height % 2 == 0 ||
      p.census_width * p.census_height - 1 > 64)
    throw Error(where, "census window must be odd x odd with at most 65 pixels");
  if (p.p1 < 0 || p.p2 < p.p1 || p.p2 > 1000) throw Error(where, "need 0 <= p1 <= p2 <= 1000");
  Geometry g{left.cols,          left.rows,           p.num_disparities,
             p.census_width / 2, p.census_height / 2, p.census_width * p.census_height - 1};
  cv::Mat pl, pr;
  cv::copyMakeBorder(left, pl, g.ry, g.ry, g.rx, g.rx, cv::BORDER_REPLICATE);
  cv::copyMakeBorder(right, pr, g.ry, g.ry, g.rx, g.rx, cv::BORDER_REPLICATE);
  DisparityImage out(g.W, g.H, kNaN);
  const int outside = std::max(p.cost_box, 1) * ((p.census_width * p.census_height - 1) / 2);
  if (p.cost_box < 1 || p.cost_box % 2 == 0 || p.cost_box > 9) throw Error(where, "cost_box must be odd, 1..9");
  // Intensity-adaptive P2 (Hirschmüller 2008: P2 = P2' / |I(p) - I(p-r)|), here
  // P2 / (1 + step / p2_step) and at least P1: depth edges usually coincide with grey edges.
  std::vector<int> lut(256);
  for (int k = 0; k < 256; ++k)
    lut[std::size_t(k)] = p.p2_step > 0 ? std::max(p.p1, int(std::lround(p.p2 / (1.0 + double(k) / p.p2_step)))) : p.p2;
  const int bands = (p.bands >= 2 && g.H >= 2) ? 2 : 1;
  std::vector<BandJob> jobs;
  if (bands == 1) {
    jobs.push_back(
        {&pl, &pr, g, p.p1, p.p2, p.uniqueness_ratio, p.lr_check, outside, p.cost_box, lut.data(), 0, g.H, 1, &out});
  } else {
    const int top = g.H / 2;
    jobs.push_back(
        {&pl, &pr, g, p.p1, p.p2, p.uniqueness_ratio, p.lr_check, outside, p.cost_box, lut.data(), 0, top, 1, &out});
    jobs.push_back({&pl, &pr, g, p.p1, p.p2, p.uniqueness_ratio, p.lr_check, outside, p.cost_box, lut.data(), g.H - 1,
                    g.H - top, -1, &out});
  }
  const bool avx2 = p.allow_avx2 && cropsight::detail::cpu_has_avx2_fma();
  // One thread per band (the bands write disjoint rows).
  cropsight::detail::parallel_for(jobs.size(), int(jobs.size()), 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) (avx2 ? sweep_band_avx2 : sweep_band_portable)(jobs[i]);
  });
  return out;
}

}  // namespace cropsight::stereo::detail
