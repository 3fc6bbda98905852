#include "cloud_conversions.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::ros_io {

namespace {

sensor_msgs::PointField field(const char* name, std::uint32_t offset, std::uint8_t type) {
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = type;
  f.count = 1;
  return f;
}

const sensor_msgs::PointField* find_field(const sensor_msgs::PointCloud2& c, const std::string& name) {
  for (const auto& f : c.fields)
    if (f.name == name) return &f;
  return nullptr;
}

// R G B bytes as the float32 `rgb` field holds them in PCL's packing: 0x00RRGGBB.
std::uint32_t pack_rgb(const std::uint8_t* rgb) {
  return std::uint32_t(rgb[0]) << 16 | std::uint32_t(rgb[1]) << 8 | std::uint32_t(rgb[2]);
}

// Least squares of y = a x + b over the pairs; false when x has no spread.
struct LineFit {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  long n = 0;
  void add(double x, double y) {
    sx += x, sy += y, sxx += x * x, sxy += x * y, syy += y * y;
    ++n;
  }
  bool solve(double& a, double& b, double& rms) const {
    const double den = double(n) * sxx - sx * sx;
    if (n < 3 || !(std::abs(den) > 1e-12 * double(n) * double(n))) return false;
    a = (double(n) * sxy - sx * sy) / den;
    b = (sy - a * sx) / double(n);
    // Residual sum of squares from the sums: Σ(y - a x - b)².
    const double rss = syy + a * a * sxx + double(n) * b * b - 2 * a * sxy - 2 * b * sy + 2 * a * b * sx;
    rms = std::sqrt(std::max(0.0, rss) / double(n));
    return true;
  }
};

}  // namespace

void append_cloud(const Cloud& cloud, FlatCloud& out) {
  out.xyz.reserve(out.xyz.size() + 3 * cloud.size());
  for (const auto& p : cloud.points) out.xyz.insert(out.xyz.end(), {p.x(), p.y(), p.z()});
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (int k = 0; k < 3; ++k)
      out.rgb.push_back(cloud.has_colors() ? std::uint8_t(std::lround(std::clamp(cloud.colors[i][k], 0.f, 1.f) * 255.f))
                                           : std::uint8_t(0));
  if (cloud.has_labels())
    out.labels.insert(out.labels.end(), cloud.labels.begin(), cloud.labels.end());
  else
    out.labels.resize(out.labels.size() + cloud.size(), 0);
}

sensor_msgs::PointCloud2 make_cloud(const std::vector<float>& xyz, const std::vector<std::uint8_t>* rgb,
                                    const std::vector<int>* labels) {
  using PF = sensor_msgs::PointField;
  sensor_msgs::PointCloud2 pc;
  pc.height = 1;
  pc.width = std::uint32_t(xyz.size() / 3);
  pc.fields = {field("x", 0, PF::FLOAT32), field("y", 4, PF::FLOAT32), field("z", 8, PF::FLOAT32)};
  std::uint32_t step = 12;
  if (rgb) pc.fields.push_back(field("rgb", step, PF::FLOAT32)), step += 4;
  if (labels) pc.fields.push_back(field("label", step, PF::INT32)), step += 4;
  pc.point_step = step;
  pc.row_step = step * pc.width;
  pc.is_bigendian = false;
  pc.is_dense = true;
  pc.data.resize(std::size_t(pc.row_step));
  for (std::size_t i = 0; i < pc.width; ++i) {
    std::uint8_t* p = pc.data.data() + i * step;
    std::memcpy(p, &xyz[3 * i], 12);
    std::uint32_t off = 12;
    if (rgb) {
      const std::uint32_t packed = pack_rgb(&(*rgb)[3 * i]);
      std::memcpy(p + off, &packed, 4);
      off += 4;
    }
    if (labels) {
      const std::int32_t l = (*labels)[i];
      std::memcpy(p + off, &l, 4);
    }
  }
  return pc;
}

sensor_msgs::PointCloud2 organised_cloud_from_frame(const bridge::FrameBuffers& f) {
  using PF = sensor_msgs::PointField;
  const bridge::CameraModel& cam = f.camera;
  const bool color = !f.rgb.empty();
  sensor_msgs::PointCloud2 pc;
  pc.width = std::uint32_t(cam.width);
  pc.height = std::uint32_t(cam.height);
  pc.fields = {field("x", 0, PF::FLOAT32), field("y", 4, PF::FLOAT32), field("z", 8, PF::FLOAT32)};
  if (color) pc.fields.push_back(field("rgb", 12, PF::FLOAT32));
  pc.point_step = color ? 16 : 12;
  pc.row_step = pc.point_step * pc.width;
  pc.is_bigendian = false;
  pc.is_dense = false;
  pc.data.resize(std::size_t(pc.row_step) * pc.height);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const std::size_t i = std::size_t(v) * std::size_t(cam.width) + std::size_t(u);
      float xyz[3] = {nan, nan, nan};
      if (f.depth[i] > 0) {
        const double z = f.depth[i] * cam.depth_scale;
        xyz[0] = float((u - cam.cx) * z / cam.fx);
        xyz[1] = float((v - cam.cy) * z / cam.fy);
        xyz[2] = float(z);
      }
      std::uint8_t* p = pc.data.data() + i * pc.point_step;
      std::memcpy(p, xyz, 12);
      if (color) {
        const std::uint32_t packed = pack_rgb(&f.rgb[3 * i]);
        std::memcpy(p + 12, &packed, 4);
      }
    }
  return pc;
}

bridge::FrameBuffers frame_from_organised_cloud(const sensor_msgs::PointCloud2& c, double depth_scale, bool want_color,
                                                const std::string& topic) {
  using PF = sensor_msgs::PointField;
  if (c.height <= 1) throw Error(topic, "cloud is not organised (height " + std::to_string(c.height) + ")");
  if (c.width == 0 || c.width > 100000 || c.height > 100000)
    throw Error(topic,
                "cloud size " + std::to_string(c.width) + "x" + std::to_string(c.height) + " is not an image size");
  if (c.is_bigendian) throw Error(topic, "big-endian clouds are not supported");
  const PF* fx_ = find_field(c, "x");
  const PF* fy_ = find_field(c, "y");
  const PF* fz_ = find_field(c, "z");
  for (const PF* f : {fx_, fy_, fz_})
    if (!f || f->datatype != PF::FLOAT32) throw Error(topic, "cloud needs float32 fields x, y and z");
  const PF* frgb = want_color ? find_field(c, "rgb") : nullptr;
  if (want_color && !frgb) frgb = find_field(c, "rgba");
  if (want_color && !frgb) throw Error(topic, "colour wanted (~use_color) but the cloud has no rgb or rgba field");
  for (const PF* f : {fx_, fy_, fz_, frgb})
    if (f && std::size_t(f->offset) + 4 > c.point_step)
      throw Error(topic, "field '" + f->name + "' lies outside point_step " + std::to_string(c.point_step));
  if (std::size_t(c.row_step) < std::size_t(c.point_step) * c.width)
    throw Error(topic, "row_step " + std::to_string(c.row_step) + " is shorter than width x point_step");
  if (c.data.size() < std::size_t(c.row_step) * c.height)
    throw Error(topic, "data has " + std::to_string(c.data.size()) + " bytes, row_step x height needs " +
                           std::to_string(std::size_t(c.row_step) * c.height));
  if (!(depth_scale > 0)) throw Error(topic, "depth_scale must be > 0");

  bridge::FrameBuffers f;
  const int w = int(c.width), h = int(c.height);
  f.camera.width = w;
  f.camera.height = h;
  f.camera.depth_scale = depth_scale;
  f.depth.assign(std::size_t(w) * std::size_t(h), 0);
  if (frgb) f.rgb.assign(3 * f.depth.size(), 0);
  LineFit fit_u, fit_v;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const std::uint8_t* p = c.data.data() + std::size_t(v) * c.row_step + std::size_t(u) * c.point_step;
      float x, y, z;
      std::memcpy(&x, p + fx_->offset, 4);
      std::memcpy(&y, p + fy_->offset, 4);
      std::memcpy(&z, p + fz_->offset, 4);
      const std::size_t i = std::size_t(v) * std::size_t(w) + std::size_t(u);
      if (frgb) {
        std::uint32_t packed;
        std::memcpy(&packed, p + frgb->offset, 4);
        f.rgb[3 * i] = std::uint8_t(packed >> 16);
        f.rgb[3 * i + 1] = std::uint8_t(packed >> 8);
        f.rgb[3 * i + 2] = std::uint8_t(packed);
      }
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !(z > 0)) continue;
      const double raw = std::round(double(z) / depth_scale);
      if (raw < 1 || raw > 65535) continue;  // beyond 16-bit depth: no return
      f.depth[i] = std::uint16_t(raw);
      fit_u.add(double(x) / z, u);
      fit_v.add(double(y) / z, v);
    }
  double rms_u = 0, rms_v = 0;
  if (!fit_u.solve(f.camera.fx, f.camera.cx, rms_u) || !fit_v.solve(f.camera.fy, f.camera.cy, rms_v))
    throw Error(topic, "too few valid points spread over the image to fit the camera intrinsics");
  if (!(f.camera.fx > 0) || !(f.camera.fy > 0))
    throw Error(topic,
                "the points do not project like a pinhole camera's (fitted focal length <= 0): is the "
                "cloud in the camera optical frame?");
  // A cloud made from a depth image fits to float precision; more than a pixel means the points
  // were moved (a transformed or filtered cloud), and depth from them would be wrong.
  if (std::max(rms_u, rms_v) > 1.0)
    throw Error(topic, "the points do not project onto their pixels (fit residual " +
                           std::to_string(std::max(rms_u, rms_v)) +
                           " px): the cloud must be in the camera optical frame, as depth_image_proc publishes it");
  return f;
}

}  // namespace cropsight::ros_io
