// The data preparation declared in point_batch.hpp.
#include "nn/torch/point_batch.hpp"

#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"

namespace cropsight::nn::torch_impl {

namespace {

// Fills row i of xyz (N,3) and feats (N,C) from point `src` with the channel order x y z
// [r g b] [nx ny nz].
void fill_point(const Prepared& p, int src, float* xyz, float* f, const Eigen::Matrix3f& R, float scale,
                const Eigen::Vector3f& jitter, const Eigen::Vector3f& dcol) {
  const Eigen::Vector3f x = scale * (R * p.xyz[std::size_t(src)]) + jitter;
  xyz[0] = x.x(), xyz[1] = x.y(), xyz[2] = x.z();
  int k = 0;
  f[k++] = x.x(), f[k++] = x.y(), f[k++] = x.z();
  if (!p.rgb.empty()) {
    const Eigen::Vector3f c = (p.rgb[std::size_t(src)] + dcol).cwiseMax(0.f).cwiseMin(1.f);
    f[k++] = c.x(), f[k++] = c.y(), f[k++] = c.z();
  }
  if (!p.n.empty()) {
    const Eigen::Vector3f n = R * p.n[std::size_t(src)];
    f[k++] = n.x(), f[k++] = n.y(), f[k++] = n.z();
  }
}

}  // namespace

Prepared prepare(const Cloud& c, const std::string& features) {
  const bool need_n = features.find('n') != std::string::npos && features != "xyz";
  const bool need_rgb = features.find("rgb") != std::string::npos;
  if (need_n && !c.has_normals()) throw Error("point network", "features '" + features + "' need normals");
  if (need_rgb && !c.has_colors()) throw Error("point network", "features '" + features + "' need colours");
  Prepared p;
  p.xyz = c.points;
  geometry::normalize_unit_sphere(p.xyz);
  if (need_n) p.n = c.normals;
  if (need_rgb) p.rgb = c.colors;
  p.labels = c.labels;
  return p;
}

Eigen::Matrix3f rotation_about_vertical(float a) {
  Eigen::Matrix3f R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}

std::tuple<torch::Tensor, torch::Tensor, torch::Tensor> make_batch(const PointNetConfig& cfg,
                                                                   const std::vector<const Prepared*>& clouds,
                                                                   const std::vector<std::vector<int>>& idx,
                                                                   std::mt19937_64* aug,
                                                                   const Eigen::Matrix3f* rotation) {
  const int64_t B = int64_t(clouds.size()), N = int64_t(idx[0].size()), C = feature_channels(cfg.features);
  auto xyz = torch::empty({B, N, 3});
  auto feats = torch::empty({B, N, C});
  auto labels = torch::zeros({B, N}, torch::kLong);
  for (int64_t b = 0; b < B; ++b) {
    Eigen::Matrix3f R = rotation ? *rotation : Eigen::Matrix3f::Identity();
    float scale = 1.f;
    Eigen::Vector3f dcol = Eigen::Vector3f::Zero();
    std::normal_distribution<float> g(0.f, float(cfg.jitter_sigma));
    if (aug) {
      std::uniform_real_distribution<float> u(0.f, 1.f);
      const float a = u(*aug) * 2.f * float(M_PI);
      R = rotation_about_vertical(a);
      scale = float(cfg.scale_min + (cfg.scale_max - cfg.scale_min) * u(*aug));
      const float cj = float(cfg.colour_jitter);
      dcol = Eigen::Vector3f::Constant((u(*aug) * 2 - 1) * cj) +
             Eigen::Vector3f((u(*aug) * 2 - 1), (u(*aug) * 2 - 1), (u(*aug) * 2 - 1)) * (cj / 2);
    }
    float* px = xyz[b].data_ptr<float>();
    float* pf = feats[b].data_ptr<float>();
    int64_t* pl = labels[b].data_ptr<int64_t>();
    for (int64_t i = 0; i < N; ++i) {
      const int src = idx[std::size_t(b)][std::size_t(i)];
      Eigen::Vector3f jit = Eigen::Vector3f::Zero();
      if (aug) jit = Eigen::Vector3f(g(*aug), g(*aug), g(*aug)).cwiseMax(-0.02f).cwiseMin(0.02f);
      fill_point(*clouds[std::size_t(b)], src, px + 3 * i, pf + C * i, R, scale, jit, dcol);
      if (!clouds[std::size_t(b)]->labels.empty()) pl[i] = clouds[std::size_t(b)]->labels[std::size_t(src)];
    }
  }
  return {xyz, feats, labels};
}

}  // namespace cropsight::nn::torch_impl
