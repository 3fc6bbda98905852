#pragma once
// Dense disparity from a rectified stereo pair (left image is the reference).
//
// compute_disparity() runs one of two semi-global matching engines (Hirschmüller 2008), chosen
// by DisparityConfig::engine:
//   - "census" (default): ours (src/stereo/census_sgm.cpp): census cost, 5 paths in one sweep
//     over the rows (two threads: top band down, bottom band up), intensity-adaptive P2,
//     uniqueness check, right-view disparities from the same summed costs (minimum along the
//     diagonals) for the left-right check, parabola sub-pixel fit; then a speckle filter;
//   - "opencv": OpenCV's StereoSGBM (the seedling pipeline's engine), with
//     - left padding so that the left-most `num_disparities` columns get a disparity too
//       (OpenCV leaves them invalid),
//     - a left-right consistency check (OpenCV's internal one, disp12MaxDiff, plus an optional
//       explicit check against a second match of the horizontally mirrored pair),
//     - matching features: rank transform + grey level (robust to exposure differences between
//       the cameras); measured on Middlebury it lowers mean bad-1 by ~1 point over raw colour,
//     - sub-pixel disparities (OpenCV's parabola fit, 1/16 px);
// both then fill holes: every invalid pixel takes the smaller (background) of its nearest valid
// left / right neighbours on the scan line, then a median over the filled pixels,
// so that every pixel gets an estimate (the "no holes on textured surfaces" rule and the
// Middlebury rule where a missing estimate counts as an error).
//
// Disparity images: pixels, float, x_left - x_right >= 0; NaN = no estimate.
#include <string>

#include "cropsight/core/config.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::stereo {

using DisparityImage = Image<float>;

/// Largest disparity search range accepted (num_disparities, --max-disp): the census engine keeps
/// width x num_disparities 16-bit costs per row buffer, so an unbounded range (say 2^20) tries to
/// allocate gigabytes and appears to hang. 1024 covers full-size Middlebury pairs.
inline constexpr int kMaxDisparities = 1024;
/// Largest rank_radius: the rank count of a (2r+1)^2 window is kept in 8 bits (r = 7: 224 < 256).
inline constexpr int kMaxRankRadius = 7;

struct DisparityConfig {
  std::string engine = "census";  ///< "census" (ours, see below) or "opencv" (StereoSGBM)
  int census_width = 5;           ///< px; census window (census engine), odd, width*height <= 65
  int census_height = 5;          ///< px; odd
  int census_p1 = 15;             ///< Hamming bits; SGM penalty of a +-1 px step (census engine)
  /// Hamming bits; SGM penalty of a larger step (census engine). 100 with census_p2_step 2: chosen
  /// on all eight shared Middlebury scenes together (was 120 / 4, tuned on the classic four)
  int census_p2 = 100;
  int census_p2_step = 2;     ///< grey levels; P2 / (1 + |dI| / this) along a path (0 = constant)
  int census_blur = 0;        ///< px; Gaussian kernel applied to the grey images before the census (0 = none)
  int census_box = 1;         ///< columns; horizontal box sum of census costs before SGM (odd; 1 = none)
  bool allow_avx2 = true;     ///< census engine: use the AVX2 kernel when the CPU has it (else SSE2)
  int num_disparities = 128;  ///< search range [min_disparity, min_disparity + num_disparities); multiple of 16
  int min_disparity = 0;      ///< pixels
  int block_size = 5;         ///< matching window side (odd)
  double p1 = 32;             ///< SGM small-jump penalty per channel per window pixel (P1 = p1*cn*bs^2)
  double p2 = 64;             ///< SGM large-jump penalty per channel per window pixel (P2 = p2*cn*bs^2)
  int uniqueness_ratio = 15;  ///< percent margin of best over second-best cost
  int speckle_window = 100;   ///< pixels; connected regions smaller than this are invalidated
  int speckle_range = 2;      ///< pixels; max disparity step inside one speckle region
  int disp12_max_diff = 1;    ///< pixels; OpenCV's internal left-right check tolerance (-1 off)
  int pre_filter_cap = 63;    ///< clip of OpenCV's x-Sobel prefilter
  int lr_check = 1;           ///< px; explicit left-right check against the mirrored match (-1 off)
  std::string mode = "3way";  ///< "sgbm" (5 paths), "hh" (8 paths), "hh4", "3way"
  bool pad_left = true;       ///< pad left so the left-most columns get a disparity
  bool fill_holes = true;     ///< fill invalid pixels (background-favouring scan-line fill + median)
  int median = 5;             ///< median window (0/1 = none) applied after filling
  bool use_color = true;      ///< match on colour when both images have colour (ignored when rank_radius > 0)
  int rank_radius = 3;        ///< px; rank-transform window radius of the matching features (0 = raw image)

  template <class V>
  void visit(V& v) {
    v("engine", engine,
      "census = our census-cost SGM (5 paths, one sweep, LR check from the same costs) | opencv = StereoSGBM");
    v("census_width", census_width,
      "px; census window width, odd (census engine; 5x5 measured best on Middlebury among 5x5..9x7)",
      Range::within(1, 65).odd());
    v("census_height", census_height, "px; census window height, odd (census engine)", Range::within(1, 65).odd());
    // The census engine's penalties are 16-bit Hamming sums (census_sgm: 0 <= p1 <= p2 <= 1000).
    v("census_p1", census_p1, "Hamming bits; SGM penalty for +-1 px disparity changes (census engine)",
      Range::within(0, 1000));
    v("census_p2", census_p2, "Hamming bits; SGM penalty for larger disparity jumps (census engine)",
      Range::within(0, 1000));
    v("census_p2_step", census_p2_step,
      "grey levels; P2 falls as P2 / (1 + |dI| / census_p2_step) across intensity edges (Hirschmueller 2008 "
      "divides by |dI|; 0 = constant P2)",
      Range::within(0, 255));
    v("census_blur", census_blur, "px; odd Gaussian kernel smoothing the grey images before the census (0 = none)",
      Range::within(0, 31));
    v("census_box", census_box, "columns; horizontal box sum of the census costs before SGM (odd, 1 = none)",
      Range::within(1, 9).odd());
    v("allow_avx2", allow_avx2, "census engine: run the AVX2 kernel when the CPU has it (false = portable SSE2)");
    v("num_disparities", num_disparities, "px; disparity search range, multiple of 16 (paper: 128 at 640x480)",
      Range::within(16, kMaxDisparities).multiple_of(16));
    v("min_disparity", min_disparity, "px; smallest disparity searched",
      Range::within(-kMaxDisparities, kMaxDisparities));
    v("block_size", block_size, "px; SGBM matching window side, odd", Range::within(1, 31).odd());
    // OpenCV silently replaces P1 <= 0 and P2 <= P1 by its own defaults (validate_disparity_config
    // says so instead); the cap keeps p * channels * block_size^2 within int.
    v("p1", p1, "SGM penalty for +-1 px disparity changes, per channel and window pixel (OpenCV sample: 8)",
      Range::within(0, 1e4).open_below());
    v("p2", p2, "SGM penalty for larger disparity jumps, per channel and window pixel (OpenCV sample: 32)",
      Range::within(0, 1e4).open_below());
    v("uniqueness_ratio", uniqueness_ratio,
      "percent; best cost must beat the second best by this margin (OpenCV sample: 10; 15 measured best here)",
      Range::within(0, 100));
    v("speckle_window", speckle_window, "px; disparity regions smaller than this are removed",
      Range::within(0, 1 << 20));
    v("speckle_range", speckle_range, "px; disparity variation allowed inside a region",
      Range::within(0, kMaxDisparities));
    v("disp12_max_diff", disp12_max_diff, "px; left-right consistency tolerance (-1 disables)",
      Range::within(-1, kMaxDisparities));
    v("pre_filter_cap", pre_filter_cap, "clip value of the x-derivative prefilter", Range::within(1, 63));
    v("lr_check", lr_check, "px; explicit left-right check tolerance against the mirrored match (-1 disables)",
      Range::within(-1, kMaxDisparities));
    v("mode", mode, "SGM variant: sgbm | hh | hh4 | 3way");
    v("pad_left", pad_left, "pad the images on the left so the left-most columns get disparities");
    v("fill_holes", fill_holes, "fill pixels without a disparity from their scan-line neighbours");
    v("median", median, "px; median window applied after hole filling (0 = none)", Range::within(0, 5));
    v("use_color", use_color, "match on colour images when available (raw-image matching only)");
    v("rank_radius", rank_radius,
      "px; match on (rank transform, grey, rank transform) features, window radius (0 = raw)",
      Range::within(0, kMaxRankRadius));
  }
};

/// Throws Error(where, "'<prefix><key>' ...") when a field of `cfg` is out of the Range declared
/// in visit() (num_disparities not a multiple of 16 in 16..kMaxDisparities, non-positive or
/// non-finite penalties, uniqueness_ratio outside 0..100, ...) or breaks a rule between fields
/// (unknown engine or mode, p2 <= p1, census window over 65 pixels, ...). `prefix` is prepended to the key
/// names ("disparity." inside pipeline::seedling::Config). compute_disparity() runs it too (where = the image).
void validate_disparity_config(const DisparityConfig& cfg, const std::string& where, const std::string& prefix = "");

/// Left-reference disparity of a rectified pair. Images must have equal, non-zero size, else
/// Error(where, ...), as is an invalid configuration (validate_disparity_config) or a search
/// range wider than the image. Colour images are matched in colour when cfg.use_color.
DisparityImage compute_disparity(const ColorImage& left, const ColorImage& right, const DisparityConfig& cfg,
                                 const std::string& where = "stereo pair");
DisparityImage compute_disparity(const GrayImage& left, const GrayImage& right, const DisparityConfig& cfg,
                                 const std::string& where = "stereo pair");

/// Plain OpenCV StereoSGBM with the parameters of OpenCV's stereo_match sample (block 3 → here
/// `block_size`, P1 = 8·cn·bs², P2 = 32·cn·bs², uniqueness 10, speckle 100/32, disp12MaxDiff 1),
/// no padding, no filling: the baseline the issue compares against. Invalid pixels are NaN.
/// `three_way`: OpenCV's faster MODE_SGBM_3WAY instead of MODE_SGBM (the speed baseline of bench_stereo).
DisparityImage opencv_sgbm_disparity(const ColorImage& left, const ColorImage& right, int num_disparities,
                                     int block_size = 3, const std::string& where = "stereo pair",
                                     bool three_way = false);

/// Winner-take-all block matching with a square window (the paper's SAD / SSD baselines, 55×55),
/// integer disparities, computed with box filters. Pixels whose window leaves the image get NaN.
/// Throws Error(where, ...) for a window that is even or outside 1..kMaxBlockWindow, or a
/// num_disparities outside 1..image width.
enum class BlockCost { kSad, kSsd };
inline constexpr int kMaxBlockWindow = 255;
DisparityImage block_matching(const GrayImage& left, const GrayImage& right, int num_disparities, int window,
                              BlockCost cost, const std::string& where = "stereo pair");

/// Grey levels (R*77 + G*150 + B*29) >> 8 of a colour image: the input of the block-matching
/// baselines (stereo disparity --method sad|ssd, eval stereo --baselines).
GrayImage grey_levels(const ColorImage& image);

/// Percent of pixels with an estimate (finite disparity); 0 for an empty image.
double valid_percent(const DisparityImage& disparity);

/// Fills NaN pixels in place: each takes the smaller of its nearest valid left / right neighbours
/// on the same row (occlusions belong to the background), then a `median`-window median is
/// applied to the filled pixels only. Rows without any valid pixel are filled from the rows above
/// or below. A disparity image with no valid pixel at all is left unchanged.
void fill_disparity_holes(DisparityImage& disparity, int median);

}  // namespace cropsight::stereo
