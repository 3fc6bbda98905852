#pragma once
// A minimal owned, row-major image. Kept free of OpenCV so that the public headers stay light;
// io/ converts to and from cv::Mat inside its .cpp files. C++17, so that results holding images
// (masks) reach the ROS nodes (built as C++17) as they are.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cropsight {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb8& a, const Rgb8& b) { return a.r == b.r && a.g == b.g && a.b == b.b; }
  friend bool operator!=(const Rgb8& a, const Rgb8& b) { return !(a == b); }
};

template <typename T>
struct Image {
  int width = 0;
  int height = 0;
  std::vector<T> data;  ///< row-major, width*height elements

  Image() = default;
  Image(int w, int h, T fill = T{}) : width(w), height(h), data(std::size_t(w) * std::size_t(h), fill) {}

  bool empty() const { return data.empty(); }
  std::size_t size() const { return data.size(); }
  T& at(int u, int v) { return data[std::size_t(v) * std::size_t(width) + std::size_t(u)]; }
  const T& at(int u, int v) const { return data[std::size_t(v) * std::size_t(width) + std::size_t(u)]; }
  T* row(int v) { return data.data() + std::size_t(v) * std::size_t(width); }
  const T* row(int v) const { return data.data() + std::size_t(v) * std::size_t(width); }
  friend bool operator==(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.data == b.data;
  }
  friend bool operator!=(const Image& a, const Image& b) { return !(a == b); }
};

using DepthImage = Image<std::uint16_t>;  ///< raw sensor units; metres = value * depth_scale; 0 = no return
using LabelImage = Image<std::uint16_t>;  ///< instance id per pixel, 0 = none
using ColorImage = Image<Rgb8>;
using GrayImage = Image<std::uint8_t>;

}  // namespace cropsight
