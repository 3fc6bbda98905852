#pragma once
// The grape segmentation pipeline's last stage behind one class and one config: which model(s),
// and how a network is run (every point, or the paper's sampled pass with carry-back, rotated
// votes, an ensemble partner and its weight). A preset (configs/grape-best.yaml: the shipped best
// recipe) fills the whole config; the CLI's flags only override its keys.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/pipeline/grape/model.hpp"

namespace cropsight::pipeline::grape {

struct SegmenterConfig {
  std::string model;                ///< model file: a network (.pt) or a GBDT (.json)
  bool sampled = false;             ///< networks: one pass on num_points samples, labels carried back
  std::string sampling = "random";  ///< sampled pass: random (as in training) or fps
  int carry_k = 4;                  ///< sampled pass: samples voting for each other point; 1 = the paper's nearest
  int votes = 1;                    ///< networks: passes rotated by 360°/votes about the vertical axis
  std::string ensemble;             ///< second model mixed in by its class probabilities ("" = none)
  double ensemble_weight = 0.5;     ///< the second model's share of the mix
  int threads = 2;

  template <class V>
  void visit(V& v) {
    v("model", model, "path; network (.pt) or GBDT (.json) model; relative paths in a preset are relative to it");
    v("sampled", sampled, "bool; networks: one pass on num_points samples, labels carried back (paper: true)");
    v("sampling", sampling, "random | fps; the sampled pass's sample (random, as the networks are trained)");
    v("carry_k", carry_k, "count; sampled pass: samples voting per other point (paper: 1; ours 4)", Range::at_least(1));
    v("votes", votes, "count; networks: rotated test-time passes, probabilities averaged (paper: 1)",
      Range::within(1, 64, "each vote is one more pass"));
    v("ensemble", ensemble, "path; second model mixed in by its class probabilities, empty = none (ours)");
    v("ensemble_weight", ensemble_weight, "1; the second model's share of the mix (ours)", Range::within(0, 1));
    v("threads", threads, "count; threads of inference", Range::within(1, kMaxThreads));
  }
  /// Throws Error(where, "'votes' must be at least 1, got 0") for the first field out of range,
  /// a `sampling` other than random / fps, and `model` empty.
  void validate(const std::string& where) const;
};

/// A preset (YAML, io::load_config_map) applied to the defaults, then `overrides` (keys of the
/// config, e.g. from the CLI's flags) applied to that. Relative `model` / `ensemble` paths of the
/// preset are taken relative to the preset file's folder; those of `overrides` as given. Errors
/// name the preset file (or `overrides_where`) and the key.
SegmenterConfig load_segmenter_config(const std::filesystem::path& preset, const ConfigMap& overrides = {},
                                      const std::string& overrides_where = "overrides");

/// What a user names as "the segmenter" (the CLI's --segmenter / --config, the grape node's
/// ~segmenter): a preset (a name under configs/ or a YAML file, load_segmenter_config) or a
/// model file (.pt, .json: that model with the default settings; `overrides` must then not set
/// `model`). Empty: the defaults with `overrides` (which must set `model`). Errors name the preset
/// file or `overrides_where` and the key.
SegmenterConfig grape_segmenter_config(const std::string& preset_or_model, const ConfigMap& overrides = {},
                                       const std::string& overrides_where = "overrides");

class Segmenter {
 public:
  /// Loads cfg.model (and cfg.ensemble) and sets how it runs. Throws Error(where, ...) naming the
  /// key for a value out of range or one the model cannot take (sampled or votes > 1 for a GBDT,
  /// whose recipe fixes its own sampling); model files' errors name the file.
  explicit Segmenter(const SegmenterConfig& cfg, const std::string& where = "grape segmenter");

  /// Label of every point (needs normals and colours; a unit-sphere normalised cloud, as the
  /// dataset's clouds and grape_roi_clouds' output).
  std::vector<int> segment(const Cloud& cloud) const { return model_.segment(cloud); }
  const SegmenterConfig& config() const { return cfg_; }
  const Model& model() const { return model_; }
  /// "sampled" or "every-point" (networks; a GBDT's recipe decides its own sampling).
  const char* mode() const { return cfg_.sampled ? "sampled" : "every-point"; }

 private:
  SegmenterConfig cfg_;
  Model model_;
};

}  // namespace cropsight::pipeline::grape
