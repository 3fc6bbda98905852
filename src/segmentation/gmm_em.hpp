// Internal: the EM of fit_gmm(), compiled twice — for the x86-64 baseline (gmm.cpp, SSE2,
// 4 float lanes) and for AVX2 + FMA (gmm_avx2.cpp, 8 lanes, chosen at run time when the CPU has
// them). The includer defines CROPSIGHT_EM_NS (the namespace of the two entry points, distinct
// per instruction set) and includes gmm_em_deps.hpp first; everything else here has internal
// linkage, so the two copies never meet in the linker. Inputs are checked by the caller.
#include "gmm_em_deps.hpp"
#include "gmm_simd.hpp"

#ifndef CROPSIGHT_EM_NS
#error "define CROPSIGHT_EM_NS before including gmm_em.hpp"
#endif

namespace cropsight::segmentation::CROPSIGHT_EM_NS {
namespace {

using simd::kLanes;
using simd::splat;
using simd::vf;

// Storage of SIMD vectors, 64-byte aligned by the allocator itself. Not std::vector<vf> with
// the default allocator: std::allocator is compiled for the baseline, where GCC caps a vector
// type's alignment at 16 bytes, so the AVX2 variant's aligned 32-byte loads would fault.
template <class T>
struct Aligned64 {
  using value_type = T;
  Aligned64() = default;
  template <class U>
  Aligned64(const Aligned64<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64})); }
  void deallocate(T* p, std::size_t) { ::operator delete (p, std::align_val_t{64}); }
  friend bool operator==(const Aligned64&, const Aligned64&) { return true; }
};
using VecF = std::vector<vf, Aligned64<vf>>;

// Responsibilities of far components are exp(-87) ≈ 1e-38 and below, and the M-step's weighted
// moments of them are subnormal floats. Intel cores take a microcode assist for every subnormal
// operand or result (measured: EM 12.1 ms instead of 0.96 ms for 4096 points, K = 10, on a Xeon
// with AVX-512), so EM runs with flush-to-zero and denormals-are-zero set in this thread's MXCSR
// and restores the caller's mode on exit. The values flushed are below 1.2e-38, far below
// anything that changes the fit.
class FlushSubnormals {
 public:
#if defined(__SSE__)
  FlushSubnormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ (bit 15) | DAZ (bit 6)
  ~FlushSubnormals() { _mm_setcsr(saved_); }

 private:
  unsigned int saved_;
#endif
};

// Points centred on their mean (float keeps full precision near the origin), structure of
// arrays in SIMD-width blocks; `mask` is 1 for real points and 0 for the padding of the last block.
struct Blocks {
  Eigen::Vector3d centre;
  int n = 0, nb = 0;
  VecF x, y, z, mask;
};

Blocks make_blocks(const std::vector<Eigen::Vector3f>& points) {
  Blocks b;
  b.n = int(points.size());
  b.nb = (b.n + kLanes - 1) / kLanes;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : points) c += p.cast<double>();
  b.centre = c / double(b.n);
  b.x.assign(b.nb, vf{});
  b.y.assign(b.nb, vf{});
  b.z.assign(b.nb, vf{});
  b.mask.assign(b.nb, vf{});
  for (int i = 0; i < b.n; ++i) {
    const Eigen::Vector3d q = points[i].cast<double>() - b.centre;
    b.x[i / kLanes][i % kLanes] = float(q.x());
    b.y[i / kLanes][i % kLanes] = float(q.y());
    b.z[i / kLanes][i % kLanes] = float(q.z());
    b.mask[i / kLanes][i % kLanes] = 1.0f;
  }
  return b;
}

Eigen::Vector3d point(const Blocks& b, int i) {
  return {b.x[i / kLanes][i % kLanes], b.y[i / kLanes][i % kLanes], b.z[i / kLanes][i % kLanes]};
}

Eigen::Matrix3d global_covariance(const Blocks& b) {
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  for (int i = 0; i < b.n; ++i) {
    const Eigen::Vector3d q = point(b, i);
    s += q * q.transpose();
  }
  return s / double(b.n);
}

// Initial model in centred coordinates: k-means++ seeds, then one nearest-seed assignment.
// Distances are computed a SIMD block at a time; only the D^2 sampling walks points one by one.
GmmModel initial_centred(const Blocks& b, const GmmConfig& cfg) {
  const int k = cfg.components, nb = b.nb;
  std::mt19937 rng(cfg.seed);
  std::vector<Eigen::Vector3d> seeds;
  seeds.push_back(point(b, std::uniform_int_distribution<int>(0, b.n - 1)(rng)));
  VecF d2(nb, splat(std::numeric_limits<float>::max()));
  VecF nearest(nb, splat(0.0f));  // index of the nearest seed, as float
  auto update = [&](int s) {
    const float sx = float(seeds[s].x()), sy = float(seeds[s].y()), sz = float(seeds[s].z());
    const vf idx = splat(float(s));
    for (int q = 0; q < nb; ++q) {
      const vf dx = b.x[q] - sx, dy = b.y[q] - sy, dz = b.z[q] - sz;
      const vf d = dx * dx + dy * dy + dz * dz;
      const auto closer = d < d2[q];
      d2[q] = closer ? d : d2[q];
      nearest[q] = closer ? idx : nearest[q];
    }
  };
  update(0);
  while (int(seeds.size()) < k) {
    double total = 0;
    for (int q = 0; q < nb; ++q) total += simd::hsum_d(d2[q] * b.mask[q]);
    int pick = b.n - 1;
    if (total > 0) {
      double u = std::uniform_real_distribution<double>(0, total)(rng);
      for (int i = 0; i < b.n; ++i) {
        u -= double(d2[i / kLanes][i % kLanes]);
        if (u <= 0) {
          pick = i;
          break;
        }
      }
    } else {
      pick = std::uniform_int_distribution<int>(0, b.n - 1)(rng);
    }
    seeds.push_back(point(b, pick));
    update(int(seeds.size()) - 1);
  }
  std::vector<int> count(k, 0);
  std::vector<Eigen::Vector3d> sum(k, Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> sq(k, Eigen::Matrix3d::Zero());
  for (int i = 0; i < b.n; ++i) {
    const int j = int(nearest[i / kLanes][i % kLanes]);
    const Eigen::Vector3d q = point(b, i);
    ++count[j];
    sum[j] += q;
    sq[j] += q * q.transpose();
  }
  const Eigen::Matrix3d fallback =
      global_covariance(b) / std::pow(double(k), 2.0 / 3.0) + cfg.min_variance * Eigen::Matrix3d::Identity();
  GmmModel m;
  for (int j = 0; j < k; ++j) {
    const double c = std::max(count[j], 1);
    const Eigen::Vector3d mean = count[j] ? Eigen::Vector3d(sum[j] / c) : seeds[j];
    Eigen::Matrix3d cov = fallback;
    if (count[j] >= 4) cov = sq[j] / c - mean * mean.transpose() + cfg.min_variance * Eigen::Matrix3d::Identity();
    m.weights.push_back(std::max(1.0, double(count[j])) / double(b.n));
    m.means.push_back(mean);
    m.covariances.push_back(cov);
  }
  double ws = 0;
  for (double w : m.weights) ws += w;
  for (double& w : m.weights) w /= ws;
  return m;
}

// Per-component constants of the log-density: log w - log|L| - 1.5 log(2 pi), the inverse
// Cholesky factor A = L^-1 (so that the Mahalanobis term is |A (x - mu)|^2) and the mean.
struct Component {
  float mx, my, mz, a11, a21, a22, a31, a32, a33, c;
};

bool make_component(const GmmModel& m, int j, Component& out) {
  Eigen::LLT<Eigen::Matrix3d> llt(m.covariances[j]);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix3d l = llt.matrixL();
  if (!(l.diagonal().array() > 0).all()) return false;
  const Eigen::Matrix3d a = l.triangularView<Eigen::Lower>().solve(Eigen::Matrix3d::Identity());
  const double log_det_l = std::log(l(0, 0)) + std::log(l(1, 1)) + std::log(l(2, 2));
  out = {float(m.means[j].x()),
         float(m.means[j].y()),
         float(m.means[j].z()),
         float(a(0, 0)),
         float(a(1, 0)),
         float(a(1, 1)),
         float(a(2, 0)),
         float(a(2, 1)),
         float(a(2, 2)),
         float(std::log(std::max(m.weights[j], 1e-300)) - log_det_l - 1.5 * std::log(2.0 * std::numbers::pi))};
  return true;
}

GmmModel uncentre(GmmModel m, const Eigen::Vector3d& c) {
  for (auto& mu : m.means) mu += c;
  return m;
}

}  // namespace

/// Initial model (k-means++ seeds, one hard assignment), in the points' frame.
GmmModel initial(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg) {
  const Blocks b = make_blocks(points);
  return uncentre(initial_centred(b, cfg), b.centre);
}

/// The EM fit; `points` finite and at least cfg.components of them. Long on purpose: the E and
/// M steps are the hot loops over the same blocked responsibilities.
GmmResult fit(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg) {
  const FlushSubnormals flush;
  const Blocks b = make_blocks(points);
  const int k = cfg.components, nb = b.nb;
  GmmModel m = initial_centred(b, cfg);
  const Eigen::Matrix3d fallback =
      global_covariance(b) / std::pow(double(k), 2.0 / 3.0) + cfg.min_variance * Eigen::Matrix3d::Identity();

  // resp[j * nb + blk]: log-density, then responsibility, of the points of block blk.
  VecF resp(std::size_t(k) * nb);
  std::vector<Component> comp(k);
  GmmResult result;
  double prev_ll = -std::numeric_limits<double>::infinity();
  std::mt19937 rng(cfg.seed + 7919u);
  for (int it = 0;; ++it) {
    // ---- E-step: log-densities, log-sum-exp normalisation, total log-likelihood.
    for (int j = 0; j < k; ++j) {
      if (!make_component(m, j, comp[j])) {
        m.covariances[j] = fallback;
        make_component(m, j, comp[j]);
      }
      const Component& c = comp[j];
      vf* out = resp.data() + std::size_t(j) * nb;
      for (int q = 0; q < nb; ++q) {
        const vf dx = b.x[q] - c.mx, dy = b.y[q] - c.my, dz = b.z[q] - c.mz;
        const vf y1 = c.a11 * dx;
        const vf y2 = c.a21 * dx + c.a22 * dy;
        const vf y3 = c.a31 * dx + c.a32 * dy + c.a33 * dz;
        out[q] = c.c - 0.5f * (y1 * y1 + y2 * y2 + y3 * y3);
      }
    }
    vf ll_acc = splat(0.0f);
    double ll = 0;
    for (int q = 0; q < nb; ++q) {
      vf mx = resp[q];
      for (int j = 1; j < k; ++j) mx = simd::vmax(mx, resp[std::size_t(j) * nb + q]);
      vf s = splat(0.0f);
      for (int j = 0; j < k; ++j) {
        vf& r = resp[std::size_t(j) * nb + q];
        r = simd::vexp(r - mx);
        s += r;
      }
      const vf inv = b.mask[q] / s;
      for (int j = 0; j < k; ++j) resp[std::size_t(j) * nb + q] *= inv;
      ll_acc += (mx + simd::vlog(s)) * b.mask[q];
      if ((q & 63) == 63) {  // flush to double now and then: float sums of thousands drift
        ll += simd::hsum_d(ll_acc);
        ll_acc = splat(0.0f);
      }
    }
    ll += simd::hsum_d(ll_acc);
    result.iterations = it;
    if (std::isfinite(prev_ll) && std::fabs(ll - prev_ll) < cfg.tolerance * std::fabs(ll)) {
      result.converged = true;
      result.log_likelihood = ll / double(b.n);
      break;
    }
    if (it >= cfg.max_iterations) {
      result.log_likelihood = ll / double(b.n);
      break;
    }
    prev_ll = ll;

    // ---- M-step: weighted moments per component (centred coordinates).
    for (int j = 0; j < k; ++j) {
      const vf* r = resp.data() + std::size_t(j) * nb;
      vf s0{}, sx{}, sy{}, sz{}, sxx{}, sxy{}, sxz{}, syy{}, syz{}, szz{};
      for (int q = 0; q < nb; ++q) {
        const vf w = r[q], x = b.x[q], y = b.y[q], z = b.z[q];
        const vf wx = w * x, wy = w * y, wz = w * z;
        s0 += w;
        sx += wx, sy += wy, sz += wz;
        sxx += wx * x, sxy += wx * y, sxz += wx * z;
        syy += wy * y, syz += wy * z, szz += wz * z;
      }
      const double nk = simd::hsum_d(s0);
      if (nk < 1e-3) {  // empty component: restart it at a random point
        m.weights[j] = 1.0 / double(b.n);
        m.means[j] = point(b, std::uniform_int_distribution<int>(0, b.n - 1)(rng));
        m.covariances[j] = fallback;
        continue;
      }
      const Eigen::Vector3d mu(simd::hsum_d(sx) / nk, simd::hsum_d(sy) / nk, simd::hsum_d(sz) / nk);
      Eigen::Matrix3d cov;
      cov(0, 0) = simd::hsum_d(sxx) / nk;
      cov(0, 1) = cov(1, 0) = simd::hsum_d(sxy) / nk;
      cov(0, 2) = cov(2, 0) = simd::hsum_d(sxz) / nk;
      cov(1, 1) = simd::hsum_d(syy) / nk;
      cov(1, 2) = cov(2, 1) = simd::hsum_d(syz) / nk;
      cov(2, 2) = simd::hsum_d(szz) / nk;
      cov -= mu * mu.transpose();
      cov += cfg.min_variance * Eigen::Matrix3d::Identity();
      m.weights[j] = nk / double(b.n);
      m.means[j] = mu;
      m.covariances[j] = cov;
    }
    double ws = 0;
    for (double w : m.weights) ws += w;
    for (double& w : m.weights) w /= ws;
  }

  result.labels.assign(b.n, 0);
  for (int i = 0; i < b.n; ++i) {
    const int q = i / kLanes, lane = i % kLanes;
    float best = -1.0f;
    for (int j = 0; j < k; ++j) {
      const float r = resp[std::size_t(j) * nb + q][lane];
      if (r > best) best = r, result.labels[i] = j;
    }
  }
  result.model = uncentre(std::move(m), b.centre);
  return result;
}

}  // namespace cropsight::segmentation::CROPSIGHT_EM_NS
