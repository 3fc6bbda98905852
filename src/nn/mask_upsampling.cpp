// MaskScores (mask_upsampling.hpp): the mask head's scores at image pixels.
#include "nn/mask_upsampling.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "nn/onnx_decode.hpp"

namespace cropsight::nn {

namespace {

// One axis of a CellMap: `pixels` image pixels at `scale` input pixels each after `pad` pixels of
// letterbox border, onto `cells` cells of `cell` input pixels.
void axis_cells(int pixels, float scale, int pad, float cell, int cells, bool bilinear, std::vector<int>& c0,
                std::vector<int>& c1, std::vector<float>& w) {
  c0.resize(std::size_t(pixels));
  c1.resize(std::size_t(pixels));
  w.assign(std::size_t(pixels), 0.0f);
  for (int i = 0; i < pixels; ++i) {
    const float at = ((float(i) + 0.5f) * scale + float(pad)) / cell;  // in cells; centres at k + 0.5
    if (!bilinear) {
      c0[std::size_t(i)] = c1[std::size_t(i)] = std::clamp(int(std::floor(at)), 0, cells - 1);
      continue;
    }
    const float f = at - 0.5f;
    const int k = int(std::floor(f));
    if (k < 0 || k >= cells - 1) {  // beyond the first or last centre: that cell alone
      c0[std::size_t(i)] = c1[std::size_t(i)] = k < 0 ? 0 : cells - 1;
      continue;
    }
    c0[std::size_t(i)] = k;
    c1[std::size_t(i)] = k + 1;
    w[std::size_t(i)] = f - float(k);
  }
}

// The cell map of a mask head of out_w x out_h cells computed from an input_w x input_h letterbox.
CellMap cell_map(int out_w, int out_h, int input_w, int input_h, bool bilinear, int image_w, int image_h) {
  const Letterbox lb = Letterbox::fit(image_w, image_h, input_w, input_h, OnnxResize::letterbox);
  const float sx = float(input_w) / float(out_w), sy = float(input_h) / float(out_h);
  CellMap m;
  axis_cells(image_w, lb.scale_x, lb.pad_x, sx, out_w, bilinear, m.x0, m.x1, m.wx);
  axis_cells(image_h, lb.scale_y, lb.pad_y, sy, out_h, bilinear, m.y0, m.y1, m.wy);
  return m;
}

// Calls f(u, score) for every pixel u in [u0, u1) of image row v of class plane p (out_w cells a
// row): the cells under the span are mixed once into `line` (one value per cell), then each pixel
// mixes two cells of it.
template <class F>
void for_each_score(const CellMap& m, const float* p, int out_w, int v, int u0, int u1, std::vector<float>& line,
                    F&& f) {
  const float* r0 = p + std::size_t(m.y0[std::size_t(v)]) * std::size_t(out_w);
  const float* r1 = p + std::size_t(m.y1[std::size_t(v)]) * std::size_t(out_w);
  const float wy = m.wy[std::size_t(v)];
  line.resize(std::size_t(out_w));
  // x0 and x1 grow with u, so the span's pixels read cells x0[u0] .. x1[u1 - 1] only.
  const int x_end = m.x1[std::size_t(u1 - 1)] + 1;
  for (int x = m.x0[std::size_t(u0)]; x < x_end; ++x) line[std::size_t(x)] = r0[x] + wy * (r1[x] - r0[x]);
  for (int u = u0; u < u1; ++u) {
    const float a = line[std::size_t(m.x0[std::size_t(u)])], b = line[std::size_t(m.x1[std::size_t(u)])];
    f(u, a + m.wx[std::size_t(u)] * (b - a));
  }
}

}  // namespace

MaskScores::MaskScores(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w, int image_h)
    : classes_(heads.classes), row_(std::size_t(std::max(image_w, 0))) {
  const bool bilinear = cfg.mask_upsampling != "nearest";
  add(heads.mask, heads.out_w, heads.out_h, cfg.input_width, cfg.input_height, bilinear, image_w, image_h);
  for (const auto& p : heads.extra_masks)
    add(p.mask, p.out_w, p.out_h, p.input_w, p.input_h, bilinear, image_w, image_h);
}

const float* MaskScores::row(int c, int v) { return span(c, v, 0, int(row_.size())); }

const float* MaskScores::span(int c, int v, int u0, int u1) {
  if (u0 >= u1) return row_.data();
  const float inv = 1.0f / float(passes_.size());
  for (std::size_t k = 0; k < passes_.size(); ++k) {
    const Pass& p = passes_[k];
    const float* plane = p.mask + std::size_t(c) * std::size_t(p.out_w) * std::size_t(p.out_h);
    if (k == 0)
      for_each_score(p.cells, plane, p.out_w, v, u0, u1, line_, [&](int u, float s) { row_[std::size_t(u)] = s; });
    else
      for_each_score(p.cells, plane, p.out_w, v, u0, u1, line_, [&](int u, float s) { row_[std::size_t(u)] += s; });
  }
  if (passes_.size() > 1)
    for (int u = u0; u < u1; ++u) row_[std::size_t(u)] *= inv;
  return row_.data();
}

void MaskScores::add(const std::vector<float>& mask, int out_w, int out_h, int input_w, int input_h, bool bilinear,
                     int image_w, int image_h) {
  if (out_w <= 0 || out_h <= 0 || mask.size() != std::size_t(classes_) * std::size_t(out_w) * std::size_t(out_h))
    throw Error("detector", "a mask head's size does not match its cells");
  passes_.push_back({cell_map(out_w, out_h, input_w, input_h, bilinear, image_w, image_h), mask.data(), out_w, out_h});
}

}  // namespace cropsight::nn
