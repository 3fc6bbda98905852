#include "cropsight/stereo/disparity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "census_sgm.hpp"
#include "core/parallel_for.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cv_convert.hpp"

namespace cropsight::stereo {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

int sgbm_mode(const std::string& mode, const std::string& where) {
  if (mode == "sgbm") return cv::StereoSGBM::MODE_SGBM;
  if (mode == "hh") return cv::StereoSGBM::MODE_HH;
  if (mode == "hh4") return cv::StereoSGBM::MODE_HH4;
  if (mode == "3way") return cv::StereoSGBM::MODE_SGBM_3WAY;
  throw Error(where, "unknown SGM mode '" + mode + "' (expected sgbm, hh, hh4 or 3way)");
}

void check_pair(int lw, int lh, int rw, int rh, const std::string& where) {
  if (lw <= 0 || lh <= 0) throw Error(where, "empty left image");
  if (lw != rw || lh != rh)
    throw Error(where, "left and right images differ in size (" + std::to_string(lw) + "x" + std::to_string(lh) +
                           " vs " + std::to_string(rw) + "x" + std::to_string(rh) + ")");
}

// The search range must fit the image: wider ranges only add columns that can never match, and
// an unbounded one makes the cost buffers huge (see kMaxDisparities).
void check_range(int num_disparities, int width, const std::string& where, const std::string& key) {
  if (num_disparities <= 0 || num_disparities % 16 != 0 || num_disparities > kMaxDisparities)
    throw Error(where, "'" + key + "' must be a multiple of 16 in 16.." + std::to_string(kMaxDisparities) + ", got " +
                           std::to_string(num_disparities));
  if (num_disparities > std::max(16, width))
    throw Error(where, "'" + key + "' (" + std::to_string(num_disparities) + ") exceeds the image width (" +
                           std::to_string(width) + " px)");
}

// CV_16S fixed-point (x16) disparity → float pixels, NaN where OpenCV marks invalid.
DisparityImage from_fixed(const cv::Mat& d16, int min_disparity, int x0) {
  DisparityImage out(d16.cols - x0, d16.rows, kNaN);
  const int invalid = (min_disparity - 1) * 16;
  for (int y = 0; y < d16.rows; ++y) {
    const short* s = d16.ptr<short>(y) + x0;
    float* d = out.row(y);
    for (int x = 0; x < out.width; ++x)
      if (s[x] > invalid) d[x] = float(s[x]) * (1.0f / 16.0f);
  }
  return out;
}

DisparityImage run_sgbm(const cv::Mat& left, const cv::Mat& right, const DisparityConfig& c, const std::string& where) {
  const int cn = left.channels();
  const int bs2 = c.block_size * c.block_size;
  auto sgbm = cv::StereoSGBM::create(c.min_disparity, c.num_disparities, c.block_size, int(c.p1 * cn * bs2),
                                     int(c.p2 * cn * bs2), c.disp12_max_diff, c.pre_filter_cap, c.uniqueness_ratio,
                                     c.speckle_window, c.speckle_range, sgbm_mode(c.mode, where));
  cv::Mat l = left, r = right;
  int pad = 0;
  if (c.pad_left) {
    // OpenCV only matches columns x >= min_disparity + num_disparities; padding by the search
    // range (replicated border) lets every real column be matched.
    pad = c.num_disparities + std::max(0, c.min_disparity);
    cv::copyMakeBorder(left, l, 0, 0, pad, 0, cv::BORDER_REPLICATE);
    cv::copyMakeBorder(right, r, 0, 0, pad, 0, cv::BORDER_REPLICATE);
  }
  cv::Mat d16;
  sgbm->compute(l, r, d16);
  DisparityImage out = from_fixed(d16, c.min_disparity, pad);
  if (c.lr_check >= 0) {
    // Explicit left-right check: match the mirrored pair (mirrored right image as reference),
    // mirror the result back to get the right view's disparity, and drop left pixels whose
    // partner disagrees by more than lr_check px (occlusions, mismatches, fattened edges).
    cv::Mat fl, fr, r16;
    cv::flip(right, fl, 1);
    cv::flip(left, fr, 1);
    if (pad > 0) {
      cv::copyMakeBorder(fl, fl, 0, 0, pad, 0, cv::BORDER_REPLICATE);
      cv::copyMakeBorder(fr, fr, 0, 0, pad, 0, cv::BORDER_REPLICATE);
    }
    sgbm->compute(fl, fr, r16);
    DisparityImage rd = from_fixed(r16, c.min_disparity, pad);
    const int w = out.width;
    for (int y = 0; y < out.height; ++y) {
      float* row = out.row(y);
      const float* rr = rd.row(y);  // mirrored: right-view column xr is at w-1-xr
      for (int x = 0; x < w; ++x) {
        if (std::isnan(row[x])) continue;
        const int xr = int(std::lround(float(x) - row[x]));
        if (xr < 0 || xr >= w) {
          row[x] = kNaN;
          continue;
        }
        const float dr = rr[w - 1 - xr];
        if (std::isnan(dr) || std::fabs(dr - row[x]) > float(c.lr_check)) row[x] = kNaN;
      }
    }
  }
  if (pad > 0 && c.lr_check < 0) {
    // A match inside the replicated padding is no match: the point is out of the right view.
    for (int y = 0; y < out.height; ++y) {
      float* row = out.row(y);
      for (int x = 0; x < out.width; ++x)
        if (row[x] > float(x)) row[x] = kNaN;
    }
  }
  if (c.fill_holes) fill_disparity_holes(out, c.median);
  return out;
}

// Rank transform (Zabih & Woodfill 1994): the number of window pixels darker than the centre,
// scaled to 0..255. It is invariant to monotonic brightness changes between the two cameras
// (exposure, vignetting), which the raw-intensity cost of SGBM is not. Returned as three
// channels (rank, grey, rank) so that SGBM's colour cost weighs the rank twice the intensity.
cv::Mat rank_features(const cv::Mat& image, int radius) {
  cv::Mat gray;
  if (image.channels() == 3)
    cv::cvtColor(image, gray, cv::COLOR_RGB2GRAY);
  else
    gray = image;
  cv::Mat padded;
  cv::copyMakeBorder(gray, padded, radius, radius, radius, radius, cv::BORDER_REPLICATE);
  const int w = gray.cols, h = gray.rows, n = (2 * radius + 1) * (2 * radius + 1);
  cv::Mat count(h, w, CV_8U, cv::Scalar(0));
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* c = padded.ptr<std::uint8_t>(y + radius) + radius;
    std::uint8_t* out = count.ptr<std::uint8_t>(y);
    for (int dy = -radius; dy <= radius; ++dy) {
      const std::uint8_t* row = padded.ptr<std::uint8_t>(y + radius + dy) + radius;
      for (int dx = -radius; dx <= radius; ++dx) {
        const std::uint8_t* q = row + dx;
        for (int x = 0; x < w; ++x) out[x] = std::uint8_t(out[x] + (q[x] < c[x] ? 1 : 0));
      }
    }
  }
  cv::Mat scaled;
  count.convertTo(scaled, CV_8U, 255.0 / double(n - 1));
  cv::Mat channels[] = {scaled, gray, scaled}, merged;
  cv::merge(channels, 3, merged);
  return merged;
}

// Threads of the post-processing passes below: the census engine's two bands (census_sgm.hpp).
constexpr int kPostThreads = 2;

// Removes small disparity islands (OpenCV's filterSpeckles on a 1/16 px fixed-point copy): the
// census engine's equivalent of SGBM's built-in speckle filter. The conversions run on two
// threads (rows are independent); filterSpeckles itself is one flood fill.
void remove_speckles(DisparityImage& disp, int window, int range) {
  if (window <= 0) return;
  cv::Mat d16(disp.height, disp.width, CV_16S);
  const auto rows = std::size_t(disp.height);
  cropsight::detail::parallel_for(rows, kPostThreads, 32, [&](std::size_t b, std::size_t e) {
    for (std::size_t y = b; y < e; ++y) {
      const float* s = disp.row(int(y));
      short* o = d16.ptr<short>(int(y));
      for (int x = 0; x < disp.width; ++x) o[x] = std::isnan(s[x]) ? short(-16) : short(std::lround(s[x] * 16.0f));
    }
  });
  cv::filterSpeckles(d16, -16, window, range * 16);
  cropsight::detail::parallel_for(rows, kPostThreads, 32, [&](std::size_t b, std::size_t e) {
    for (std::size_t y = b; y < e; ++y) {
      const short* o = d16.ptr<short>(int(y));
      float* s = disp.row(int(y));
      for (int x = 0; x < disp.width; ++x)
        if (o[x] == -16) s[x] = kNaN;
    }
  });
}

DisparityImage run_census(const cv::Mat& left, const cv::Mat& right, const DisparityConfig& c,
                          const std::string& where) {
  // Grey levels, optionally Gaussian-smoothed: sensor noise flips census bits wherever the
  // texture has little contrast (soil, leaves), which shows as off-by-one matches.
  auto gray = [&c](const cv::Mat& m) {
    cv::Mat g;
    if (m.channels() == 1)
      g = m;
    else
      cv::cvtColor(m, g, cv::COLOR_RGB2GRAY);
    if (c.census_blur == 0) return g;
    cv::Mat s;
    cv::GaussianBlur(g, s, cv::Size(c.census_blur, c.census_blur), 0);
    return s;
  };
  detail::CensusSgmParams p;
  p.num_disparities = c.num_disparities;
  p.census_width = c.census_width;
  p.census_height = c.census_height;
  p.p1 = c.census_p1;
  p.p2 = c.census_p2;
  p.p2_step = c.census_p2_step;
  p.allow_avx2 = c.allow_avx2;
  p.cost_box = c.census_box;
  p.uniqueness_ratio = c.uniqueness_ratio;
  p.lr_check = c.lr_check;
  DisparityImage out;
  try {
    out = detail::census_sgm(gray(left), gray(right), p);
  } catch (const Error& e) {
    throw Error(where, e.problem());
  }
  remove_speckles(out, c.speckle_window, c.speckle_range);
  if (c.fill_holes) fill_disparity_holes(out, c.median);
  return out;
}

DisparityImage match(const cv::Mat& left, const cv::Mat& right, const DisparityConfig& c, const std::string& where) {
  validate_disparity_config(c, where);
  check_range(c.num_disparities, left.cols, where, "num_disparities");
  if (c.engine == "census") return run_census(left, right, c, where);
  if (c.engine != "opencv")
    throw Error(where, "unknown disparity engine '" + c.engine + "' (expected census or opencv)");
  if (c.rank_radius > 0)
    return run_sgbm(rank_features(left, c.rank_radius), rank_features(right, c.rank_radius), c, where);
  return run_sgbm(left, right, c, where);
}

}  // namespace

void validate_disparity_config(const DisparityConfig& c, const std::string& where, const std::string& prefix) {
  auto fail = [&](const char* key, const std::string& problem) {  // the rules between fields
    throw Error(where, "'" + prefix + key + "' " + problem);
  };
  if (c.engine != "census" && c.engine != "opencv") fail("engine", "must be census or opencv, got '" + c.engine + "'");
  if (c.mode != "sgbm" && c.mode != "hh" && c.mode != "hh4" && c.mode != "3way")
    fail("mode", "must be sgbm, hh, hh4 or 3way, got '" + c.mode + "'");
  check_config(c, where, prefix);
  if (c.engine == "census" && c.min_disparity != 0)
    fail("min_disparity", "must be 0 with the census engine (it searches from disparity 0)");
  if (c.census_width * c.census_height > 65)
    fail("census_width", "x census_height must be at most 65 pixels (one 64-bit census word)");
  cropsight::detail::check_range(where, prefix + "census_p2", c.census_p2, Range::at_least(c.census_p1, "census_p1"));
  if (c.census_blur != 0)
    cropsight::detail::check_range(where, prefix + "census_blur", c.census_blur,
                                   Range::within(3, 31, "0 = none").odd());
  cropsight::detail::check_range(where, prefix + "p2", c.p2, Range::above(c.p1, "p1"));
}

void fill_disparity_holes(DisparityImage& disp, int median) {
  const int w = disp.width, h = disp.height;
  if (w == 0 || h == 0) return;
  std::vector<std::uint8_t> filled(std::size_t(w) * h, 0), empty(std::size_t(h), 0);
  // Scan-line filling, row by row on two threads (each row reads and writes itself only).
  cropsight::detail::parallel_for(std::size_t(h), kPostThreads, 32, [&](std::size_t b, std::size_t e) {
    std::vector<float> left_val(static_cast<std::size_t>(w)), right_val(static_cast<std::size_t>(w));
    for (int y = int(b); y < int(e); ++y) {
      float* row = disp.row(y);
      float last = kNaN;
      for (int x = 0; x < w; ++x) {
        if (!std::isnan(row[x])) last = row[x];
        left_val[std::size_t(x)] = last;
      }
      last = kNaN;
      for (int x = w - 1; x >= 0; --x) {
        if (!std::isnan(row[x])) last = row[x];
        right_val[std::size_t(x)] = last;
      }
      if (std::isnan(left_val[std::size_t(w - 1)])) {  // no valid pixel in the row
        empty[std::size_t(y)] = 1;
        continue;
      }
      for (int x = 0; x < w; ++x) {
        if (!std::isnan(row[x])) continue;
        const float a = left_val[std::size_t(x)], c = right_val[std::size_t(x)];
        // Occluded / unmatched pixels lie behind their neighbours: take the smaller disparity.
        row[x] = std::isnan(a) ? c : std::isnan(c) ? a : std::min(a, c);
        filled[std::size_t(y) * w + x] = 1;
      }
    }
  });
  if (std::count(empty.begin(), empty.end(), std::uint8_t(1)) == h) return;
  // Rows without any estimate copy the nearest row that has one (above first), in row order.
  for (int y = 0; y < h; ++y) {
    if (!empty[std::size_t(y)]) continue;
    int src = -1;
    for (int d = 1; d < h && src < 0; ++d) {
      if (y - d >= 0 && !std::isnan(disp.row(y - d)[w - 1]) && !filled[std::size_t(y - d) * w + w - 1])
        src = y - d;
      else if (y + d < h && !std::isnan(disp.row(y + d)[w - 1]))
        src = y + d;
    }
    if (src < 0) src = y > 0 ? y - 1 : y + 1;
    std::copy(disp.row(src), disp.row(src) + w, disp.row(y));
    std::fill(filled.begin() + std::ptrdiff_t(y) * w, filled.begin() + std::ptrdiff_t(y + 1) * w, 1);
  }
  if (median <= 1) return;
  // Scan-line filling leaves horizontal streaks; a median over the filled pixels removes them
  // without touching matched pixels. Two row blocks on two threads, each median taken on its
  // rows plus the k/2 rows of context on either side that exist, so that every output pixel sees
  // the same neighbourhood (and image-border replication) as one median over the whole image.
  const int k = median >= 5 ? 5 : 3, r = k / 2;
  const cv::Mat d = detail::view(disp).clone();
  cropsight::detail::parallel_for(std::size_t(h), kPostThreads, 32, [&](std::size_t b, std::size_t e) {
    const int y0 = int(b), y1 = int(e), c0 = std::max(y0 - r, 0), c1 = std::min(y1 + r, h);
    cv::Mat m;
    cv::medianBlur(d.rowRange(c0, c1), m, k);
    for (int y = y0; y < y1; ++y) {
      const float* s = m.ptr<float>(y - c0);
      float* row = disp.row(y);
      for (int x = 0; x < w; ++x)
        if (filled[std::size_t(y) * w + x]) row[x] = s[x];
    }
  });
}

DisparityImage compute_disparity(const ColorImage& left, const ColorImage& right, const DisparityConfig& cfg,
                                 const std::string& where) {
  check_pair(left.width, left.height, right.width, right.height, where);
  if (cfg.use_color || cfg.rank_radius > 0) return match(detail::view(left), detail::view(right), cfg, where);
  cv::Mat gl, gr;
  cv::cvtColor(detail::view(left), gl, cv::COLOR_RGB2GRAY);
  cv::cvtColor(detail::view(right), gr, cv::COLOR_RGB2GRAY);
  return match(gl, gr, cfg, where);
}

DisparityImage compute_disparity(const GrayImage& left, const GrayImage& right, const DisparityConfig& cfg,
                                 const std::string& where) {
  check_pair(left.width, left.height, right.width, right.height, where);
  return match(detail::view(left), detail::view(right), cfg, where);
}

DisparityImage opencv_sgbm_disparity(const ColorImage& left, const ColorImage& right, int num_disparities,
                                     int block_size, const std::string& where, bool three_way) {
  check_pair(left.width, left.height, right.width, right.height, where);
  check_range(num_disparities, left.width, where, "num_disparities");
  if (block_size < 1 || block_size > 31 || block_size % 2 == 0)
    throw Error(where, "block size must be odd, 1..31, got " + std::to_string(block_size));
  const int cn = 3;
  auto sgbm = cv::StereoSGBM::create(0, num_disparities, block_size, 8 * cn * block_size * block_size,
                                     32 * cn * block_size * block_size, 1, 63, 10, 100, 32,
                                     three_way ? cv::StereoSGBM::MODE_SGBM_3WAY : cv::StereoSGBM::MODE_SGBM);
  cv::Mat d16;
  sgbm->compute(detail::view(left), detail::view(right), d16);
  return from_fixed(d16, 0, 0);
}

DisparityImage block_matching(const GrayImage& left, const GrayImage& right, int num_disparities, int window,
                              BlockCost cost, const std::string& where) {
  check_pair(left.width, left.height, right.width, right.height, where);
  if (window < 1 || window % 2 == 0 || window > kMaxBlockWindow)
    throw Error(where, "block-matching window must be odd, 1.." + std::to_string(kMaxBlockWindow) + ", got " +
                           std::to_string(window));
  // Each disparity d compares columns d..w-1: a range wider than the image has no columns left.
  if (num_disparities < 1 || num_disparities > left.width)
    throw Error(where, "num_disparities must be in 1.." + std::to_string(left.width) + " (the image width), got " +
                           std::to_string(num_disparities));
  const int w = left.width, h = left.height, r = window / 2;
  cv::Mat l, rr;
  detail::view(left).convertTo(l, CV_32F);
  detail::view(right).convertTo(rr, CV_32F);
  cv::Mat best(h, w, CV_32F, cv::Scalar(std::numeric_limits<float>::max()));
  cv::Mat arg(h, w, CV_32F, cv::Scalar(kNaN));
  cv::Mat diff(h, w, CV_32F), agg;
  for (int d = 0; d < num_disparities; ++d) {
    diff.setTo(cv::Scalar(1e6f));  // columns without a partner pixel never win
    cv::Mat a = l.colRange(d, w), b = rr.colRange(0, w - d), o = diff.colRange(d, w);
    cv::absdiff(a, b, o);
    if (cost == BlockCost::kSsd) cv::multiply(o, o, o);
    cv::boxFilter(diff, agg, CV_32F, cv::Size(window, window), cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
    for (int y = 0; y < h; ++y) {
      const float* s = agg.ptr<float>(y);
      float* bb = best.ptr<float>(y);
      float* aa = arg.ptr<float>(y);
      for (int x = 0; x < w; ++x)
        if (s[x] < bb[x]) {
          bb[x] = s[x];
          aa[x] = float(d);
        }
    }
  }
  DisparityImage out(w, h, kNaN);
  for (int y = r; y < h - r; ++y) {
    const float* aa = arg.ptr<float>(y);
    for (int x = r; x < w - r; ++x) out.at(x, y) = aa[x];
  }
  return out;
}

GrayImage grey_levels(const ColorImage& c) {
  GrayImage g(c.width, c.height);
  for (std::size_t i = 0; i < c.size(); ++i)
    g.data[i] = std::uint8_t((c.data[i].r * 77 + c.data[i].g * 150 + c.data[i].b * 29) >> 8);
  return g;
}

double valid_percent(const DisparityImage& d) {
  long valid = 0;
  for (float v : d.data) valid += std::isfinite(v);
  return 100.0 * double(valid) / double(std::max<std::size_t>(1, d.size()));
}

}  // namespace cropsight::stereo
