// The potato presets beside the default: potato-fusion (classical + the shipped CNN, weighted boxes
// fusion) must stay the default preset in everything but the detector, find its model from any
// working directory, and fail with the key's name when the model is missing.
#include <gtest/gtest.h>

#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"
#include "testing/testing.hpp"

namespace {

namespace pp = cropsight::pipeline::potato;

bool is_fusion_detector_key(const std::string& key) {
  return key == "detector.backend" || key == "detector.cnn_model" || key.rfind("detector.fusion.", 0) == 0;
}

TEST(PotatoPresets, FusionPresetDiffersOnlyInTheDetector) {
  auto base = cropsight::io::load_config_map(cropsight::io::find_preset("potato"));
  auto fusion = cropsight::io::load_config_map(cropsight::io::find_preset("potato-fusion"));
  EXPECT_EQ(fusion.at("detector.backend"), "fusion");
  std::erase_if(base, [](const auto& kv) { return is_fusion_detector_key(kv.first); });
  std::erase_if(fusion, [](const auto& kv) { return is_fusion_detector_key(kv.first); });
  EXPECT_EQ(base, fusion) << "configs/potato-fusion.yaml must copy every non-detector value of configs/potato.yaml";
}

TEST(PotatoPresets, FusionPresetFindsItsModelFromAnyDirectory) {
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::temp_directory_path());
  const auto cfg = pp::load_config(cropsight::io::find_preset("potato-fusion").string());
  std::filesystem::current_path(cwd);
  ASSERT_EQ(cfg.detector.backend, pp::DetectorBackend::fusion);
  EXPECT_TRUE(std::filesystem::path(cfg.detector.cnn_model).is_absolute());
  EXPECT_TRUE(std::filesystem::exists(cfg.detector.cnn_model)) << cfg.detector.cnn_model;
  EXPECT_EQ(pp::make_detector(cfg.detector, "potato-fusion")->class_names(), std::vector<std::string>{"potato"});
}

// The message of pipeline::potato::make_detector's error for backend fusion with `cnn_model` ("" when none).
std::string fusion_detector_error(const std::string& cnn_model) {
  pp::DetectorConfig cfg;
  cfg.backend = pp::DetectorBackend::fusion;
  cfg.cnn_model = cnn_model;
  try {
    pp::make_detector(cfg, "test.yaml");
  } catch (const cropsight::Error& e) {
    return e.what();
  }
  return "";
}

TEST(PotatoPresets, FusionWithoutAModelNamesTheKey) {
  const auto message = fusion_detector_error("");
  EXPECT_NE(message.find("detector.cnn_model"), std::string::npos) << message;
  EXPECT_NE(message.find("fusion"), std::string::npos) << message;
}

TEST(PotatoPresets, FusionWithAnotherClassesCnnNamesTheFile) {
  const auto message =
      fusion_detector_error((cropsight::testing::source_dir() / "models/detector-grape.onnx").string());
  EXPECT_NE(message.find("detector-grape.onnx"), std::string::npos) << message;
  EXPECT_NE(message.find("'potato'"), std::string::npos) << message;
}

TEST(PotatoPresets, FusionFindsThePotatoesOfASharedImage) {
  // i.rf.131c...: three potatoes, each found by both detectors; the fused boxes must hold them
  // (the model trained on this image: a check of the wiring, not a measurement).
  const auto image =
      cropsight::testing::shared_data_dir() / "potato/detection/images/i.rf.131c6a11f891c8b9e8de4659d829e30e.jpg";
  CROPSIGHT_REQUIRE_DATA(image);
  const auto cfg = pp::load_config("potato-fusion");
  auto detector = pp::make_detector(cfg.detector, "potato-fusion");
  const auto color = cropsight::io::read_color(image);
  const auto boxes = detector->detect({&color, nullptr});
  int confident = 0;
  for (const auto& b : boxes) confident += b.score >= 0.3f;
  EXPECT_EQ(confident, 3);
}

}  // namespace
