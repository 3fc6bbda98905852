// Colour registered to depth by projection with an occlusion test (color_registration.hpp).
#include "cropsight/io/color_registration.hpp"

#include <yaml-cpp/yaml.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "number_text.hpp"
#include "yaml_file.hpp"
#include "yaml_key.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

std::vector<double> extrinsic_numbers(const YAML::Node& node, const std::string& key, std::size_t count,
                                      const std::string& where) {
  const YAML::Node n = node[key];
  if (!n) throw Error(where, "missing required key '" + key + "'");
  if (!n.IsSequence() || n.size() != count)
    throw Error(where, "'" + key + "' must be a list of " + std::to_string(count) + " numbers");
  std::vector<double> v;
  for (std::size_t i = 0; i < count; ++i) {
    const auto d = n[i].IsScalar() ? detail::parse_double(n[i].Scalar()) : std::nullopt;
    if (!d) throw Error(where, "'" + key + "' must hold finite numbers");
    v.push_back(*d);
  }
  return v;
}

// Where a colour-camera point lands in the colour image: pinhole, then plumb_bob distortion
// (k1 k2 p1 p2 k3) when the colour camera has coefficients.
Eigen::Vector2d project_distorted(const CameraIntrinsics& c, const Eigen::Vector3d& p) {
  double x = p.x() / p.z(), y = p.y() / p.z();
  const auto& d = c.distortion;
  if (!d.empty()) {
    const double k1 = d[0], k2 = d.size() > 1 ? d[1] : 0, p1 = d.size() > 2 ? d[2] : 0, p2 = d.size() > 3 ? d[3] : 0,
                 k3 = d.size() > 4 ? d[4] : 0;
    const double r2 = x * x + y * y, radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
    const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
    x = xd;
    y = yd;
  }
  return {c.fx * x + c.cx, c.fy * y + c.cy};
}

}  // namespace

DepthToColor read_extrinsics_yaml(const fs::path& path) {
  const std::string where = path.string();
  const YAML::Node root = detail::load_yaml_file(path);
  const bool forward = root.IsMap() && root["depth_to_color"];
  const bool inverse = root.IsMap() && root["color_to_depth"];
  if (forward == inverse)
    throw Error(where,
                "expected one mapping 'depth_to_color' or 'color_to_depth' with rotation (9 numbers, "
                "row-major) and translation (3 numbers, metres)");
  const std::string name = forward ? "depth_to_color" : "color_to_depth";
  const YAML::Node m = root[name];
  if (!m.IsMap()) throw Error(where, "expected rotation and translation under '" + name + "'");
  // A typo (a 'rotaton' beside the rotation) must not pass unnoticed.
  for (const auto& kv : root)
    if (detail::yaml_key(kv.first, where) != name) throw Error(where, "unknown key '" + kv.first.Scalar() + "'");
  for (const auto& kv : m) {
    const std::string key = detail::yaml_key(kv.first, where);
    if (key != "rotation" && key != "translation") throw Error(where, "unknown key '" + name + "." + key + "'");
  }
  const std::vector<double> r = extrinsic_numbers(m, "rotation", 9, where);
  const std::vector<double> t = extrinsic_numbers(m, "translation", 3, where);
  DepthToColor e;
  e.rotation = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.data());
  e.translation = Eigen::Vector3d(t[0], t[1], t[2]);
  const double orthogonality =
      (e.rotation.transpose() * e.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthogonality > 1e-3 || std::abs(e.rotation.determinant() - 1.0) > 1e-3)
    throw Error(where, "'rotation' is not a rotation matrix (R^T R must be I and det R = 1)");
  if (inverse) {
    e.rotation.transposeInPlace();
    e.translation = -(e.rotation * e.translation);
  }
  return e;
}

// Two passes over the depth pixels: the first keeps, per colour pixel, the nearest surface that
// lands on it (a z-buffer, each point covering the colour pixels of its footprint, so that a
// sparser depth image still hides what lies behind); the second gives each depth pixel its colour
// pixel's colour when it is that nearest surface.
ColorImage register_color(const DepthImage& depth, const CameraIntrinsics& dc, const ColorImage& color,
                          const CameraIntrinsics& cc, const DepthToColor& e) {
  ColorImage out(depth.width, depth.height);  // black where nothing is registered
  const int cw = color.width, ch = color.height;
  std::vector<float> zbuffer(std::size_t(cw) * std::size_t(ch), std::numeric_limits<float>::infinity());
  std::vector<Eigen::Vector3f> at(depth.data.size(), Eigen::Vector3f(-1, -1, 0));  // colour u, v, z per depth pixel
  // A depth pixel covers about fx_colour / fx_depth colour pixels across; it marks the colour
  // pixels within half of that (none beside its own until colour is twice as fine), since a wider
  // mark would hide the far side of every depth edge.
  const int reach = int(std::floor(0.5 * std::max(cc.fx / dc.fx, cc.fy / dc.fy)));
  for (int v = 0; v < depth.height; ++v)
    for (int u = 0; u < depth.width; ++u) {
      const std::uint16_t raw = depth.at(u, v);
      if (raw == 0) continue;
      const double z = raw * dc.depth_scale;
      const Eigen::Vector3d p((u - dc.cx) / dc.fx * z, (v - dc.cy) / dc.fy * z, z);
      const Eigen::Vector3d q = e.rotation * p + e.translation;
      if (q.z() <= 0) continue;
      const Eigen::Vector2d px = project_distorted(cc, q);
      const int cu = int(std::lround(px.x())), cv = int(std::lround(px.y()));
      if (cu < 0 || cv < 0 || cu >= cw || cv >= ch) continue;
      at[std::size_t(v) * std::size_t(depth.width) + std::size_t(u)] =
          Eigen::Vector3f(float(cu), float(cv), float(q.z()));
      for (int y = std::max(0, cv - reach); y <= std::min(ch - 1, cv + reach); ++y)
        for (int x = std::max(0, cu - reach); x <= std::min(cw - 1, cu + reach); ++x) {
          float& zb = zbuffer[std::size_t(y) * std::size_t(cw) + std::size_t(x)];
          zb = std::min(zb, float(q.z()));
        }
    }
  for (std::size_t i = 0; i < at.size(); ++i) {
    const Eigen::Vector3f& a = at[i];
    if (a.z() <= 0) continue;
    const std::size_t c = std::size_t(a.y()) * std::size_t(cw) + std::size_t(a.x());
    // Hidden when a surface more than 2 cm (or 2 %) nearer covers this colour pixel: depth noise
    // on one surface stays well inside that.
    if (a.z() > zbuffer[c] + std::max(0.02f, 0.02f * a.z())) continue;
    out.data[i] = color.data[c];
  }
  return out;
}

}  // namespace cropsight::io
