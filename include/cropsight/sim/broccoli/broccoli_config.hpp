#pragma once
// Every parameter of the broccoli-field simulator (docs/simulator.md explains the model).
//
// Defaults are the `uk` preset (variety Ironman; configs/sim-broccoli-uk.yaml repeats them and
// configs/sim-broccoli-spain.yaml changes what differs). Sources in the doc strings:
//   [issue2]    the project's field brief, which summarises the papers' field set-up
//   [kusumam]   Kusumam et al. 2017, "3D-vision based detection, localization, and sizing of
//               broccoli heads in the field", J. Field Robotics (Kinect v2 on a tractor, UK and
//               Spain datasets, 7.5 / 3.3 / 6.4 fps)
//   [kinect2]   Kinect v2 ToF specification (512x424, 70.6 x 60 deg, 0.5-4.5 m range)
//   [tof]       ToF noise theory (Lange 2000: sigma ~ sqrt(A + B) / A for signal amplitude A and
//               background B) fitted to Kinect v2 studies (Fankhauser et al. 2015: about 1-2 mm
//               axial noise at 1 m, growing with range and incidence angle)
//   [agro]      agronomic typical values (plant architecture, soil), chosen by us and stated as
//               such; change them in the presets.
//
// Field frame: x along the row (driving direction), y across the rows (left of the driver),
// z up; z = 0 is the mean soil surface. Lengths in metres, angles in degrees, unless `_mm`.
#include <string>
#include <vector>

namespace cropsight::sim {

struct SimCameraConfig {
  int width = 512;
  int height = 424;
  double hfov_deg = 70.6;
  double vfov_deg = 60.0;
  double height_m = 1.25;
  double lateral_offset_m = 0.0;
  int supersample = 2;
  double min_range_m = 0.5;
  double max_range_m = 4.5;
  double tilt_deg = 0.0;
  double tilt_azimuth_deg = 0.0;
  template <class V>
  void visit(V& v) {
    v("width", width, "px; depth image width (kinect2: 512)");
    v("height", height, "px; depth image height (kinect2: 424)");
    v("hfov_deg", hfov_deg, "deg; horizontal field of view (kinect2: 70.6)");
    v("vfov_deg", vfov_deg, "deg; vertical field of view (kinect2: 60)");
    v("height_m", height_m, "m; camera height above mean soil, looking straight down (issue2: 1.25 uk, 1.40 spain)");
    v("lateral_offset_m", lateral_offset_m, "m; camera y in the field frame (0 = centred on the row layout)");
    v("supersample", supersample,
      "samples per pixel side; >1 renders sub-pixels so edge pixels can mix depths (flying pixels)");
    v("min_range_m", min_range_m, "m; no return closer than this (kinect2: 0.5)");
    v("max_range_m", max_range_m, "m; no return farther than this (kinect2: 4.5)");
    v("tilt_deg", tilt_deg,
      "deg; optical axis tilted this much from straight down (0 = nadir; a loosely mounted or sloping rig). The "
      "poses record the position only: the tilt is written to groundtruth.json's attributes");
    v("tilt_azimuth_deg", tilt_azimuth_deg,
      "deg; the direction the optical axis leans towards, from field +x (along the row) towards +y");
  }
};

struct SimMotionConfig {
  double speed_mps = 0.3;
  double fps = 7.5;
  double start_x_m = 0.0;
  double speed_jitter = 0.03;
  double height_jitter_m = 0.004;
  double lateral_jitter_m = 0.003;
  template <class V>
  void visit(V& v) {
    v("speed_mps", speed_mps, "m/s; tractor speed along the row (issue2/kusumam: about 0.3)");
    v("fps", fps, "frames per second (kusumam datasets: 7.5, 3.3 and 6.4)");
    v("start_x_m", start_x_m, "m; camera x at frame 0");
    v("speed_jitter", speed_jitter, "relative std of the per-frame advance (uneven ground, clutch) [agro]");
    v("height_jitter_m", height_jitter_m, "m; std of the camera height bounce (suspension) [agro]");
    v("lateral_jitter_m", lateral_jitter_m, "m; std of the camera lateral sway [agro]");
  }
};

struct SimFieldConfig {
  std::string variety = "uk";
  int rows_under_camera = 2;
  double row_spacing_m = 0.60;
  double in_row_spacing_m = 0.38;
  double spacing_jitter_m = 0.04;
  double row_wobble_m = 0.025;
  double missing_plant_prob = 0.04;
  double harvested_prob = 0.08;
  double weed_density_m2 = 6.0;
  template <class V>
  void visit(V& v) {
    v("variety", variety, "name recorded in groundtruth.json (issue2: uk = Ironman, spain = Titanium)");
    v("rows_under_camera", rows_under_camera,
      "rows centred in the view: 2 = camera between two rows, 1 = above one (issue2: 2 uk, 1 spain)");
    v("row_spacing_m", row_spacing_m, "m; distance between rows (issue2: 0.60 uk, 0.90 spain)");
    v("in_row_spacing_m", in_row_spacing_m, "m; plant spacing within a row (issue2: 0.38 uk, 0.30 spain)");
    v("spacing_jitter_m", spacing_jitter_m, "m; std of a plant's offset along the row from the nominal spacing [agro]");
    v("row_wobble_m", row_wobble_m, "m; std of a plant's offset across the row [agro]");
    v("missing_plant_prob", missing_plant_prob, "probability that a planting position is empty [agro]");
    v("harvested_prob", harvested_prob,
      "probability that a plant's head was already cut (stem stump, no head) (issue2: some harvested)");
    v("weed_density_m2", weed_density_m2, "weeds per square metre (issue2: weeds) [agro]");
  }
};

struct SimPlantConfig {
  double plant_height_m = 0.60;
  double head_top_min_m = 0.40;
  double head_top_max_m = 0.50;
  double stem_radius_m = 0.022;
  int leaf_count_min = 8;
  int leaf_count_max = 14;
  double leaf_length_min_m = 0.28;
  double leaf_length_max_m = 0.42;
  double leaf_width_ratio = 0.42;
  double leaf_blade_exponent = 0.7;
  double leaf_blade_fullness = 1.0;
  double leaf_elevation_min_deg = 40.0;
  double leaf_elevation_max_deg = 70.0;
  double leaf_droop_min_deg = 30.0;
  double leaf_droop_max_deg = 70.0;
  double leaf_cup = 0.25;
  double leaf_ruffle_m = 0.008;
  double leaf_rim_step_min_m = 0.03;
  double leaf_rim_step_max_m = 0.08;
  double leaf_rim_clearance_m = 0.015;
  double leaf_rim_touch_prob = 0.1;
  int inner_leaves_min = 1;
  int inner_leaves_max = 3;
  double inner_leaf_length_min_m = 0.14;
  double inner_leaf_length_max_m = 0.24;
  double inner_leaf_curl_min_deg = 100.0;
  double inner_leaf_curl_max_deg = 135.0;
  double inner_leaf_gap_max_m = 0.03;
  template <class V>
  void visit(V& v) {
    v("plant_height_m", plant_height_m,
      "m; canopy top above soil; leaf tips are scaled to reach about this (issue2: about 0.60)");
    v("head_top_min_m", head_top_min_m, "m; lowest head apex above soil [agro]");
    v("head_top_max_m", head_top_max_m, "m; highest head apex above soil [agro]");
    v("stem_radius_m", stem_radius_m, "m; main stem radius [agro]");
    v("leaf_count_min", leaf_count_min, "outer leaves per plant, minimum (issue2: 8)");
    v("leaf_count_max", leaf_count_max, "outer leaves per plant, maximum (issue2: 14)");
    v("leaf_length_min_m", leaf_length_min_m, "m; outer leaf length incl. petiole, minimum [agro]");
    v("leaf_length_max_m", leaf_length_max_m, "m; outer leaf length incl. petiole, maximum [agro]");
    v("leaf_width_ratio", leaf_width_ratio, "blade width / leaf length [agro]");
    v("leaf_blade_exponent", leaf_blade_exponent,
      "blade outline: width(u) = sin(pi u^e) along the blade u in [0, 1]; e < 1 puts the widest point towards the "
      "tip (obovate), e near 1 in the middle (lanceolate), e < 0.6 makes it round (ovate/rounded) [agro]");
    v("leaf_blade_fullness", leaf_blade_fullness,
      "blade outline: the width profile is raised to this power; < 1 = full, rounded blades, > 1 = pointed [agro]");
    v("leaf_elevation_min_deg", leaf_elevation_min_deg,
      "deg; outer leaf angle above horizontal at the stem, minimum [agro]");
    v("leaf_elevation_max_deg", leaf_elevation_max_deg,
      "deg; outer leaf angle above horizontal at the stem, maximum [agro]");
    v("leaf_droop_min_deg", leaf_droop_min_deg, "deg; how much the blade bends down from base to tip, minimum [agro]");
    v("leaf_droop_max_deg", leaf_droop_max_deg, "deg; how much the blade bends down from base to tip, maximum [agro]");
    v("leaf_cup", leaf_cup, "cupping of the blade across its width, fraction of the half width [agro]");
    v("leaf_ruffle_m", leaf_ruffle_m, "m; amplitude of the wavy leaf margin [agro]");
    v("leaf_rim_step_min_m", leaf_rim_step_min_m,
      "m; an outer leaf's midrib leaves the head's outline (+ leaf_rim_clearance_m) at least this far (drawn per "
      "leaf up to leaf_rim_step_max_m) below the lowest point of the head's rim: the petioles attach to the thick "
      "stem below the head and must go out before they rise past it, so the head rim stands on a visible depth "
      "step over the leaves next to it (papers' field images). Leaves drawn higher move down the stem (and lean "
      "outward when too steep); leaves drawn lower are kept [agro]");
    v("leaf_rim_step_max_m", leaf_rim_step_max_m, "m; largest drawn rim step of an outer leaf [agro]");
    v("leaf_rim_clearance_m", leaf_rim_clearance_m,
      "m; horizontal distance beyond the head's widest semi-axis at which the rim step is enforced [agro]");
    v("leaf_rim_touch_prob", leaf_rim_touch_prob,
      "probability that an outer leaf's rim step is 0: it meets the head rim at the rim's height with no depth step "
      "(young leaves pressed against the head) [agro]");
    v("inner_leaves_min", inner_leaves_min,
      "young inner leaves that curl over the head, minimum (issue2: leaves partly hide the head)");
    v("inner_leaves_max", inner_leaves_max, "young inner leaves that curl over the head, maximum");
    v("inner_leaf_length_min_m", inner_leaf_length_min_m, "m; inner leaf length, minimum [agro]");
    v("inner_leaf_length_max_m", inner_leaf_length_max_m, "m; inner leaf length, maximum [agro]");
    v("inner_leaf_curl_min_deg", inner_leaf_curl_min_deg,
      "deg; inner leaf direction at the tip above horizontal (>90 = bends back over the head), minimum");
    v("inner_leaf_curl_max_deg", inner_leaf_curl_max_deg,
      "deg; inner leaf direction at the tip above horizontal, maximum");
    v("inner_leaf_gap_max_m", inner_leaf_gap_max_m,
      "m; an inner leaf rises outside the head's outline (widest semi-axis plus floret bumps) with a gap drawn in "
      "[3 mm, this] [agro]");
  }
};

struct SimHeadConfig {
  double diameter_min_mm = 60.0;
  double diameter_max_mm = 200.0;
  double immature_prob = 0.3;
  double mature_min_mm = 100.0;
  double mature_mean_mm = 140.0;
  double mature_std_mm = 25.0;
  double ellipticity_max = 0.12;
  double dome_ratio_min = 0.45;
  double dome_ratio_max = 0.70;
  double tilt_max_deg = 12.0;
  double floret_ratio = 0.16;
  double floret_height = 0.55;
  double purple_prob = 0.1;
  template <class V>
  void visit(V& v) {
    v("diameter_min_mm", diameter_min_mm, "mm; smallest head (issue2: 60)");
    v("diameter_max_mm", diameter_max_mm, "mm; largest head (issue2: 200)");
    v("immature_prob", immature_prob, "fraction of heads still immature (issue2: mature and immature)");
    v("mature_min_mm", mature_min_mm,
      "mm; immature heads are uniform in [diameter_min, mature_min); mature ones above [agro]");
    v("mature_mean_mm", mature_mean_mm, "mm; mean diameter of mature heads (normal, clipped) [agro]");
    v("mature_std_mm", mature_std_mm, "mm; std of mature head diameters [agro]");
    v("ellipticity_max", ellipticity_max, "max (a-b)/(a+b) of the head outline (issue2: slightly elliptic)");
    v("dome_ratio_min", dome_ratio_min, "dome height / head radius, minimum [agro]");
    v("dome_ratio_max", dome_ratio_max, "dome height / head radius, maximum [agro]");
    v("tilt_max_deg", tilt_max_deg, "deg; largest tilt of the head axis from vertical [agro]");
    v("floret_ratio", floret_ratio, "floret radius / head radius (florets on a phyllotactic spiral) [agro]");
    v("floret_height", floret_height, "floret bump height / floret radius [agro]");
    v("purple_prob", purple_prob, "fraction of heads with an anthocyanin (purple) tinge [agro]");
  }
};

struct SimWeedConfig {
  double size_min_m = 0.02;
  double size_max_m = 0.10;
  double height_max_m = 0.08;
  template <class V>
  void visit(V& v) {
    v("size_min_m", size_min_m, "m; smallest weed rosette radius [agro]");
    v("size_max_m", size_max_m, "m; largest weed rosette radius [agro]");
    v("height_max_m", height_max_m, "m; highest weed leaf above soil [agro]");
  }
};

struct SimSoilConfig {
  double grid_m = 0.01;
  double roughness_m = 0.010;
  double roughness_scale_m = 0.12;
  double ridge_height_m = 0.03;
  double clod_density_m2 = 60.0;
  double clod_size_min_m = 0.01;
  double clod_size_max_m = 0.045;
  double moist_fraction = 0.3;
  double reflectivity_dry = 0.30;
  double reflectivity_moist = 0.12;
  template <class V>
  void visit(V& v) {
    v("grid_m", grid_m, "m; soil mesh resolution (about 3 px at 1.25 m)");
    v("roughness_m", roughness_m, "m; amplitude of the fractal soil height noise [agro]");
    v("roughness_scale_m", roughness_scale_m, "m; horizontal scale of the coarsest noise octave [agro]");
    v("ridge_height_m", ridge_height_m, "m; height of the planting bed under each row over the furrow [agro]");
    v("clod_density_m2", clod_density_m2, "clods per square metre (issue2: rough soil) [agro]");
    v("clod_size_min_m", clod_size_min_m, "m; smallest clod radius [agro]");
    v("clod_size_max_m", clod_size_max_m, "m; largest clod radius [agro]");
    v("moist_fraction", moist_fraction, "fraction of the soil in dark moist patches (low NIR return) [agro]");
    v("reflectivity_dry", reflectivity_dry, "NIR (860 nm) reflectivity of dry soil [agro; typical 0.25-0.35]");
    v("reflectivity_moist", reflectivity_moist, "NIR reflectivity of moist soil [agro; typical 0.1-0.15]");
  }
};

struct SimSensorConfig {
  double noise_at_1m_m = 0.0015;
  double reference_reflectivity = 0.5;
  double background = 0.1;
  bool sunlight = false;
  double sunlight_background = 3.0;
  double sunlight_dropout = 0.03;
  double amplitude_min = 0.06;
  double amplitude_softness = 0.02;
  double random_dropout = 0.003;
  double edge_threshold_m = 0.02;
  double flying_prob = 0.5;
  double edge_dropout_prob = 0.3;
  double color_noise = 3.0;
  std::string model = "tof";
  double stereo_noise_at_1m_m = 0.003;
  double stereo_hole_fraction = 0.05;
  double stereo_hole_scale_px = 12.0;
  double stereo_edge_dropout_prob = 0.6;
  template <class V>
  void visit(V& v) {
    v("noise_at_1m_m", noise_at_1m_m,
      "m; axial depth noise std for a reference surface head-on at 1 m (tof: Kinect v2 about 1-2 mm)");
    v("reference_reflectivity", reference_reflectivity, "NIR reflectivity of the reference surface for noise_at_1m_m");
    v("background", background,
      "ambient light relative to the reference return at 1 m (tof: B in sigma ~ sqrt(A+B)/A)");
    v("sunlight", sunlight, "simulate direct sunlight: background rises to sunlight_background, extra dropout");
    v("sunlight_background", sunlight_background,
      "ambient light relative to the reference return under direct sun [tof]");
    v("sunlight_dropout", sunlight_dropout,
      "extra probability of no return per pixel under direct sun (saturation) [tof]");
    v("amplitude_min", amplitude_min,
      "relative amplitude (reflectivity x cos(incidence) / z^2, reference = 1) at which half the returns are lost: "
      "dark and grazing surfaces [tof]");
    v("amplitude_softness", amplitude_softness, "width of the logistic amplitude dropout curve [tof]");
    v("random_dropout", random_dropout, "probability of a missing return anywhere [kinect2]");
    v("edge_threshold_m", edge_threshold_m, "m; sub-pixel depth spread above which a pixel straddles a discontinuity");
    v("flying_prob", flying_prob,
      "probability that a straddling pixel returns a mixed (flying) depth between fore- and background [tof]");
    v("edge_dropout_prob", edge_dropout_prob,
      "probability that a straddling pixel is dropped (driver's flying-pixel filter) [kinect2/libfreenect2]");
    v("color_noise", color_noise, "std of per-channel colour noise, 8-bit levels");
    v("model", model,
      "tof = Kinect v2 time of flight (the fields above); stereo = a RealSense-like active stereo camera: depth "
      "noise grows with the square of the range, blob-shaped holes, dropouts at depth edges (no flying pixels)");
    v("stereo_noise_at_1m_m", stereo_noise_at_1m_m,
      "m; stereo: depth noise std at 1 m, sigma = this x z^2 (disparity noise; RealSense D4xx about 2-5 mm at 1 m)");
    v("stereo_hole_fraction", stereo_hole_fraction,
      "stereo: fraction of the image lost in holes (failed matches on textureless or specular patches)");
    v("stereo_hole_scale_px", stereo_hole_scale_px, "px; stereo: typical hole size");
    v("stereo_edge_dropout_prob", stereo_edge_dropout_prob,
      "stereo: probability that a pixel straddling a depth edge has no depth (left-right check, occlusion "
      "shadow); otherwise it keeps the foreground surface");
  }
};

struct SimLightConfig {
  double sun_elevation_deg = 55.0;
  double sun_azimuth_deg = 30.0;
  double ambient = 0.45;
  template <class V>
  void visit(V& v) {
    v("sun_elevation_deg", sun_elevation_deg, "deg; light direction above the horizon (colour shading only)");
    v("sun_azimuth_deg", sun_azimuth_deg, "deg; light azimuth from field +x towards +y");
    v("ambient", ambient, "ambient share of the colour shading (overcast sky)");
  }
};

/// Domain randomisation (docs/simulator.md, "Randomised fields"): when enabled, every sequence
/// draws its own field, plants, heads, soil, camera and sensor from these ranges, from the seed
/// (sim/broccoli/broccoli_randomize.hpp). Each range is {min, max}, drawn uniformly per sequence;
/// the values drawn replace the preset's. Defaults = configs/sim-broccoli-random.yaml (training
/// ranges); configs/sim-broccoli-random-wide.yaml widens them for held-out evaluation.
struct SimRandomizeConfig {
  bool enabled = false;
  std::vector<double> camera_height_m{1.10, 1.50};
  std::vector<double> camera_tilt_deg{0.0, 3.0};
  double one_row_prob = 0.5;
  std::vector<double> row_spacing_m{0.55, 0.95};
  std::vector<double> in_row_spacing_m{0.28, 0.45};
  std::vector<double> leaf_family_weights{1.0, 1.0, 1.0};
  std::vector<double> leaf_count{6, 16};
  std::vector<double> leaf_length_m{0.24, 0.50};
  std::vector<double> leaf_elevation_deg{30, 75};
  std::vector<double> leaf_droop_deg{15, 80};
  std::vector<double> leaf_ruffle_m{0.0, 0.02};
  std::vector<double> plant_height_m{0.45, 0.70};
  std::vector<double> head_diameter_mm{50, 180};
  std::vector<double> head_dome_ratio{0.35, 0.80};
  std::vector<double> floret_ratio{0.05, 0.22};
  std::vector<double> floret_height{0.05, 0.80};
  std::vector<double> head_below_canopy_m{0.04, 0.25};
  std::vector<double> inner_leaves{0, 5};
  std::vector<double> soil_roughness_m{0.003, 0.025};
  std::vector<double> clod_density_m2{0, 120};
  std::vector<double> weed_density_m2{0, 25};
  double stereo_prob = 0.25;
  std::vector<double> tof_noise_at_1m_m{0.001, 0.004};
  std::vector<double> tof_flying_prob{0.2, 0.8};
  std::vector<double> tof_amplitude_min{0.03, 0.12};
  std::vector<double> random_dropout{0.001, 0.02};
  std::vector<double> stereo_noise_at_1m_m{0.002, 0.006};
  std::vector<double> stereo_hole_fraction{0.02, 0.15};
  double sunlight_prob = 0.2;
  template <class V>
  void visit(V& v) {
    v("enabled", enabled,
      "draw every sequence's field from the ranges below, from the seed (simulate broccoli --randomize); off = the "
      "preset as written");
    v("camera_height_m", camera_height_m, "m; camera height above the soil {min, max} (held-back generator: 1.1-1.5)");
    v("camera_tilt_deg", camera_tilt_deg, "deg; optical axis tilt from nadir {min, max}, towards a random azimuth");
    v("one_row_prob", one_row_prob, "probability of one row under the camera (else two)");
    v("row_spacing_m", row_spacing_m, "m; distance between rows {min, max}");
    v("in_row_spacing_m", in_row_spacing_m, "m; plant spacing within a row {min, max} (dense = canopy closes)");
    v("leaf_family_weights", leaf_family_weights,
      "relative weights of the leaf shape families {pointed/lanceolate, broad ovate/rounded, the presets' "
      "obovate}; a sequence draws one family");
    v("leaf_count", leaf_count, "outer leaves per plant {min, max}; a sequence draws a window of 2-6 inside");
    v("leaf_length_m", leaf_length_m, "m; outer leaf length {min, max}; a sequence draws a window inside");
    v("leaf_elevation_deg", leaf_elevation_deg, "deg; outer leaf angle at the stem {min, max}");
    v("leaf_droop_deg", leaf_droop_deg, "deg; blade droop from base to tip {min, max}");
    v("leaf_ruffle_m", leaf_ruffle_m, "m; wavy-margin amplitude {min, max} (0 = flat margins)");
    v("plant_height_m", plant_height_m, "m; canopy top above the soil {min, max}");
    v("head_diameter_mm", head_diameter_mm,
      "mm; head diameters {min, max} (held-back generator: 50-180): a sequence's heads span a window of it");
    v("head_dome_ratio", head_dome_ratio, "dome height / head radius {min, max}");
    v("floret_ratio", floret_ratio, "floret radius / head radius {min, max} (small = mm-scale bumps)");
    v("floret_height", floret_height, "floret bump height / floret radius {min, max} (0.05 = a smooth dome)");
    v("head_below_canopy_m", head_below_canopy_m,
      "m; how far the highest head apex lies below the canopy top {min, max} (large = heads sunk in the leaves)");
    v("inner_leaves", inner_leaves, "young leaves curling over each head {min, max} (leaves over heads: occlusion)");
    v("soil_roughness_m", soil_roughness_m, "m; soil height noise amplitude {min, max}");
    v("clod_density_m2", clod_density_m2, "clods per square metre {min, max}");
    v("weed_density_m2", weed_density_m2, "weeds per square metre {min, max}");
    v("stereo_prob", stereo_prob, "probability that a sequence uses the stereo sensor model (else Kinect v2 ToF)");
    v("tof_noise_at_1m_m", tof_noise_at_1m_m, "m; ToF axial noise at 1 m {min, max}");
    v("tof_flying_prob", tof_flying_prob,
      "ToF: probability of a flying (mixed) pixel at a depth edge {min, max}; the rest of the edge pixels split "
      "between dropped and foreground");
    v("tof_amplitude_min", tof_amplitude_min,
      "ToF: amplitude of half dropout {min, max} (higher = more grazing-angle and dark-surface dropouts, the "
      "losses multipath interference causes at grazing incidence)");
    v("random_dropout", random_dropout, "probability of a missing return anywhere {min, max}");
    v("stereo_noise_at_1m_m", stereo_noise_at_1m_m, "m; stereo noise at 1 m {min, max}");
    v("stereo_hole_fraction", stereo_hole_fraction, "stereo: image fraction in holes {min, max}");
    v("sunlight_prob", sunlight_prob, "probability of direct sunlight (ToF background, extra dropout)");
  }
};

struct BroccoliSimConfig {
  SimCameraConfig camera;
  SimMotionConfig motion;
  SimFieldConfig field;
  SimPlantConfig plant;
  SimHeadConfig head;
  SimWeedConfig weed;
  SimSoilConfig soil;
  SimSensorConfig sensor;
  SimLightConfig light;
  SimRandomizeConfig randomize;
  template <class V>
  void visit(V& v) {
    v("camera", camera, "");
    v("motion", motion, "");
    v("field", field, "");
    v("plant", plant, "");
    v("head", head, "");
    v("weed", weed, "");
    v("soil", soil, "");
    v("sensor", sensor, "");
    v("light", light, "");
    v("randomize", randomize, "");
  }
  /// Throws Error(where, ...) when a value is out of range.
  void validate(const std::string& where) const;
};

}  // namespace cropsight::sim
