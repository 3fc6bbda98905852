#include "ros_conversions.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::ros_io {

namespace {
std::string size_text(std::uint32_t w, std::uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

// The checks every image reader needs: size equal to the camera's, a step that holds a row, data
// that holds every row.
void check_layout(const sensor_msgs::Image& im, const bridge::CameraModel& cam, int bytes_per_pixel,
                  const std::string& topic) {
  if (int(im.width) != cam.width || int(im.height) != cam.height)
    throw Error(topic, "image is " + size_text(im.width, im.height) + ", camera_info says " +
                           size_text(std::uint32_t(cam.width), std::uint32_t(cam.height)));
  const std::size_t row = std::size_t(im.width) * std::size_t(bytes_per_pixel);
  if (im.step < row)
    throw Error(topic,
                "step " + std::to_string(im.step) + " is shorter than a row (" + std::to_string(row) + " bytes)");
  if (im.data.size() < std::size_t(im.step) * im.height)
    throw Error(topic, "data has " + std::to_string(im.data.size()) + " bytes, step x height needs " +
                           std::to_string(std::size_t(im.step) * im.height));
}
}  // namespace

bridge::CameraModel camera_from_info(const sensor_msgs::CameraInfo& info, double depth_scale,
                                     const std::string& topic) {
  bridge::CameraModel c;
  c.width = int(info.width);
  c.height = int(info.height);
  c.fx = info.K[0];
  c.fy = info.K[4];
  c.cx = info.K[2];
  c.cy = info.K[5];
  c.depth_scale = depth_scale;
  if (info.width == 0 || info.height == 0 || info.width > 100000 || info.height > 100000)
    throw Error(topic, "camera_info size " + size_text(info.width, info.height) + " is not an image size");
  for (double v : {c.fx, c.fy, c.cx, c.cy})
    if (!std::isfinite(v)) throw Error(topic, "camera_info K holds a non-finite value");
  if (c.fx <= 0 || c.fy <= 0) throw Error(topic, "camera_info K has a focal length <= 0 (uncalibrated camera?)");
  if (info.distortion_model == "plumb_bob" || info.distortion_model == "rational_polynomial") {
    c.distortion = info.D;
    bool zero = true;
    for (double d : c.distortion) zero = zero && d == 0;
    if (zero) c.distortion.clear();
  }
  return c;
}

sensor_msgs::CameraInfo info_from_camera(const bridge::CameraModel& c) {
  sensor_msgs::CameraInfo info;
  info.width = std::uint32_t(c.width);
  info.height = std::uint32_t(c.height);
  info.distortion_model = "plumb_bob";
  info.D = c.distortion;
  if (info.D.empty()) info.D.assign(5, 0.0);
  info.K = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {c.fx, 0, c.cx, 0, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  return info;
}

std::vector<std::uint16_t> depth_from_image(const sensor_msgs::Image& im, const bridge::CameraModel& cam,
                                            const std::string& topic) {
  // Encoding and layout are checked before the output is allocated: the size comes from a
  // camera_info that may be malformed (up to 100000 x 100000), the data bound it.
  const bool raw16 = im.encoding == "16UC1" || im.encoding == "mono16";
  if (!raw16 && im.encoding != "32FC1")
    throw Error(topic, "depth encoding '" + im.encoding + "' is not 16UC1, mono16 or 32FC1");
  check_layout(im, cam, raw16 ? 2 : 4, topic);
  if (!raw16 && im.is_bigendian) throw Error(topic, "big-endian 32FC1 depth is not supported");
  std::vector<std::uint16_t> out(std::size_t(cam.width) * std::size_t(cam.height));
  if (raw16) {
    for (int v = 0; v < cam.height; ++v) {
      const std::uint8_t* src = im.data.data() + std::size_t(v) * im.step;
      std::uint16_t* dst = out.data() + std::size_t(v) * std::size_t(cam.width);
      std::memcpy(dst, src, std::size_t(cam.width) * 2);
      if (im.is_bigendian)
        for (int u = 0; u < cam.width; ++u) dst[u] = std::uint16_t((dst[u] >> 8) | (dst[u] << 8));
    }
  } else {
    for (int v = 0; v < cam.height; ++v) {
      const std::uint8_t* src = im.data.data() + std::size_t(v) * im.step;
      for (int u = 0; u < cam.width; ++u) {
        float m;
        std::memcpy(&m, src + 4 * std::size_t(u), 4);
        const double raw = std::isfinite(m) && m > 0 ? std::round(m / cam.depth_scale) : 0.0;
        out[std::size_t(v) * std::size_t(cam.width) + std::size_t(u)] =
            raw > std::numeric_limits<std::uint16_t>::max() ? 0 : std::uint16_t(raw);
      }
    }
  }
  return out;
}

std::vector<std::uint8_t> rgb_from_image(const sensor_msgs::Image& im, const bridge::CameraModel& cam,
                                         const std::string& topic) {
  int channels = 0;
  bool bgr = false;
  if (im.encoding == "rgb8")
    channels = 3;
  else if (im.encoding == "bgr8")
    channels = 3, bgr = true;
  else if (im.encoding == "rgba8")
    channels = 4;
  else if (im.encoding == "bgra8")
    channels = 4, bgr = true;
  else if (im.encoding == "mono8")
    channels = 1;
  else
    throw Error(topic, "colour encoding '" + im.encoding + "' is not rgb8, bgr8, rgba8, bgra8 or mono8");
  check_layout(im, cam, channels, topic);
  std::vector<std::uint8_t> out(3 * std::size_t(cam.width) * std::size_t(cam.height));
  for (int v = 0; v < cam.height; ++v) {
    const std::uint8_t* src = im.data.data() + std::size_t(v) * im.step;
    std::uint8_t* dst = out.data() + 3 * std::size_t(v) * std::size_t(cam.width);
    for (int u = 0; u < cam.width; ++u, src += channels, dst += 3) {
      if (channels == 1) {
        dst[0] = dst[1] = dst[2] = src[0];
      } else {
        dst[0] = src[bgr ? 2 : 0];
        dst[1] = src[1];
        dst[2] = src[bgr ? 0 : 2];
      }
    }
  }
  return out;
}

sensor_msgs::Image image_from_depth(const std::vector<std::uint16_t>& depth, int width, int height) {
  sensor_msgs::Image im;
  im.width = std::uint32_t(width);
  im.height = std::uint32_t(height);
  im.encoding = "16UC1";
  im.is_bigendian = 0;
  im.step = std::uint32_t(width) * 2;
  im.data.resize(depth.size() * 2);
  std::memcpy(im.data.data(), depth.data(), im.data.size());
  return im;
}

sensor_msgs::Image image_from_rgb(const std::vector<std::uint8_t>& rgb, int width, int height) {
  sensor_msgs::Image im;
  im.width = std::uint32_t(width);
  im.height = std::uint32_t(height);
  im.encoding = "rgb8";
  im.is_bigendian = 0;
  im.step = std::uint32_t(width) * 3;
  im.data = rgb;
  return im;
}

}  // namespace cropsight::ros_io
