#include "cropsight/sim/renderer.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "core/parallel_for.hpp"

namespace cropsight::sim {

Eigen::Matrix3d field_to_camera_rotation() {
  Eigen::Matrix3d R;
  R << 0, 1, 0,  //
      1, 0, 0,   //
      0, 0, -1;
  return R;
}

Eigen::Matrix3d tilted_camera_rotation(double tilt_deg, double azimuth_deg) {
  if (tilt_deg == 0.0) return field_to_camera_rotation();
  constexpr double kDeg = 3.141592653589793 / 180.0;
  // The optical axis (field -z) swings towards (cos az, sin az, 0): a rotation about the
  // horizontal axis perpendicular to it.
  const Eigen::Vector3d axis(std::sin(azimuth_deg * kDeg), -std::cos(azimuth_deg * kDeg), 0.0);
  const Eigen::Matrix3d camera_to_field_tilt = Eigen::AngleAxisd(tilt_deg * kDeg, axis).toRotationMatrix();
  return field_to_camera_rotation() * camera_to_field_tilt.transpose();
}

Eigen::Vector3d camera_to_field(const Eigen::Vector3d& p_camera, const Eigen::Vector3d& camera_position) {
  return camera_position + field_to_camera_rotation().transpose() * p_camera;
}

void SampleBuffers::reset(int w, int h) {
  width = w;
  height = h;
  const std::size_t n = std::size_t(w) * std::size_t(h);
  depth.assign(n, std::numeric_limits<float>::infinity());
  label.assign(n, 0);
  kind.assign(n, SurfaceKind::soil);
  color.assign(n, Eigen::Vector3f::Zero());
  nir.assign(n, 0.f);
}

CameraIntrinsics supersampled(const CameraIntrinsics& c, int f) {
  CameraIntrinsics s = c;
  s.width = c.width * f;
  s.height = c.height * f;
  s.fx = c.fx * f;
  s.fy = c.fy * f;
  s.cx = (c.cx + 0.5) * f - 0.5;
  s.cy = (c.cy + 0.5) * f - 0.5;
  return s;
}

namespace {

struct ProjectedVertex {
  float x, y, iz;  // image position (samples), 1/z
};

struct TriSetup {
  // Edge equations w_k(x, y) = a_k x + b_k y + c_k, normalised so that w0 + w1 + w2 = 1.
  double a[3], b[3], c[3];
  int x0, x1, y0, y1;  // inclusive sample bounds
  std::uint32_t v[3];  // global vertex indices
  std::uint16_t label;
  SurfaceKind kind;
};

constexpr int kBand = 16;  // rows per parallel task

}  // namespace

// Long on purpose: the simulator's hot path; its numbered steps share the projected vertex buffers.
void render(const std::vector<const Mesh*>& meshes, const Eigen::Vector3d& C, const CameraIntrinsics& cam,
            const RenderOptions& opt, SampleBuffers& out) {
  out.reset(cam.width, cam.height);
  const Eigen::Matrix3d R = opt.field_to_camera;
  // 1. Vertices to the camera (parallel over meshes; offsets fixed in mesh order).
  std::vector<std::size_t> offset(meshes.size() + 1, 0);
  for (std::size_t m = 0; m < meshes.size(); ++m) offset[m + 1] = offset[m] + meshes[m]->position.size();
  std::vector<ProjectedVertex> pv(offset.back());
  std::vector<Eigen::Vector3f> pcolor(opt.attributes ? offset.back() : 0);
  std::vector<float> pnir(opt.attributes ? offset.back() : 0);
  cropsight::detail::parallel_for_each_index(meshes.size(), [&](std::size_t m) {
    const Mesh& mesh = *meshes[m];
    for (std::size_t i = 0; i < mesh.position.size(); ++i) {
      const Eigen::Vector3d p = R * (mesh.position[i].cast<double>() - C);
      const std::size_t g = offset[m] + i;
      const double iz = p.z() > 1e-3 ? 1.0 / p.z() : -1.0;
      pv[g] = {float(cam.fx * p.x() * iz + cam.cx), float(cam.fy * p.y() * iz + cam.cy), float(iz)};
      if (opt.attributes) {
        pcolor[g] = mesh.color[i];
        const Eigen::Vector3d ray = p.normalized();
        const double cosi = std::abs(ray.dot(R * mesh.normal[i].cast<double>()));
        pnir[g] = float(mesh.reflectivity[i] * cosi);
      }
    }
  });

  // 2. Triangle set-up and binning into bands, in mesh/triangle order (the tie-break order).
  const int bands = (cam.height + kBand - 1) / kBand;
  std::vector<TriSetup> tris;
  std::vector<std::vector<std::uint32_t>> band_tris(static_cast<std::size_t>(bands));
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const Mesh& mesh = *meshes[m];
    for (std::size_t t = 0; t < mesh.tri.size(); ++t) {
      if (opt.heads_only && mesh.tri_kind[t] != SurfaceKind::head) continue;
      TriSetup s;
      bool behind = false;
      double x[3], y[3];
      for (int k = 0; k < 3; ++k) {
        s.v[k] = std::uint32_t(offset[m] + mesh.tri[t][k]);
        const auto& q = pv[s.v[k]];
        if (q.iz <= 0) behind = true;
        x[k] = q.x;
        y[k] = q.y;
      }
      if (behind) continue;  // the scene never comes that close to the camera
      const double minx = std::min({x[0], x[1], x[2]}), maxx = std::max({x[0], x[1], x[2]});
      const double miny = std::min({y[0], y[1], y[2]}), maxy = std::max({y[0], y[1], y[2]});
      s.x0 = std::max(0, int(std::ceil(minx)));
      s.x1 = std::min(cam.width - 1, int(std::floor(maxx)));
      s.y0 = std::max(0, int(std::ceil(miny)));
      s.y1 = std::min(cam.height - 1, int(std::floor(maxy)));
      if (s.x0 > s.x1 || s.y0 > s.y1) continue;
      const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
      if (std::abs(area) < 1e-12) continue;
      for (int k = 0; k < 3; ++k) {
        // w_k is the normalised signed area opposite vertex k.
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        s.a[k] = (y[i] - y[j]) / area;
        s.b[k] = (x[j] - x[i]) / area;
        s.c[k] = (x[i] * y[j] - x[j] * y[i]) / area;
      }
      s.label = mesh.tri_label[t];
      s.kind = mesh.tri_kind[t];
      const auto id = std::uint32_t(tris.size());
      tris.push_back(s);
      for (int b = s.y0 / kBand; b <= s.y1 / kBand; ++b) band_tris[std::size_t(b)].push_back(id);
    }
  }

  // 3. Rasterise bands in parallel; each band owns its rows, triangles in fixed order.
  constexpr double kEps = -1e-9;  // inclusive edges: shared edges leave no cracks
  cropsight::detail::parallel_for_each_index(std::size_t(bands), [&](std::size_t band_index) {
    const int band = int(band_index);
    const int r0 = band * kBand, r1 = std::min(cam.height - 1, r0 + kBand - 1);
    for (std::uint32_t id : band_tris[std::size_t(band)]) {
      const TriSetup& s = tris[id];
      const ProjectedVertex& p0 = pv[s.v[0]];
      const ProjectedVertex& p1 = pv[s.v[1]];
      const ProjectedVertex& p2 = pv[s.v[2]];
      for (int yy = std::max(r0, s.y0); yy <= std::min(r1, s.y1); ++yy) {
        for (int xx = s.x0; xx <= s.x1; ++xx) {
          const double w0 = s.a[0] * xx + s.b[0] * yy + s.c[0];
          const double w1 = s.a[1] * xx + s.b[1] * yy + s.c[1];
          const double w2 = s.a[2] * xx + s.b[2] * yy + s.c[2];
          if (w0 < kEps || w1 < kEps || w2 < kEps) continue;
          const double iz = w0 * p0.iz + w1 * p1.iz + w2 * p2.iz;
          const float z = float(1.0 / iz);
          const std::size_t o = std::size_t(yy) * std::size_t(cam.width) + std::size_t(xx);
          if (!(z < out.depth[o])) continue;
          out.depth[o] = z;
          out.label[o] = s.label;
          if (opt.attributes) {
            const float q0 = float(w0 * p0.iz / iz), q1 = float(w1 * p1.iz / iz), q2 = float(w2 * p2.iz / iz);
            out.kind[o] = s.kind;
            out.color[o] = q0 * pcolor[s.v[0]] + q1 * pcolor[s.v[1]] + q2 * pcolor[s.v[2]];
            out.nir[o] = q0 * pnir[s.v[0]] + q1 * pnir[s.v[1]] + q2 * pnir[s.v[2]];
          }
        }
      }
    }
  });
}

}  // namespace cropsight::sim
