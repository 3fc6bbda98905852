// One way to build a pipeline: every crop's make_pipeline from a PipelineSpec, with shipped names
// resolved, sets applied and refused the way the CLI's --set is.
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/grape/make_pipeline.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/make_pipeline.hpp"
#include "testing/testing.hpp"

namespace pipeline_spec_test {
using cropsight::Error;
using cropsight::testing::error_message;
namespace pl = cropsight::pipeline;

TEST(MakePipeline, BroccoliDefaultsToTheGeneralModelAndTakesSets) {
  const auto general = pl::broccoli::make_pipeline({});
  EXPECT_NE(general->detector().model(), nullptr);
  const auto uk = pl::broccoli::make_pipeline({.sets = {"track=false", "oes.min_size=40"}, .model = "broccoli-oes-uk"});
  EXPECT_FALSE(uk->config().track);
  EXPECT_EQ(uk->config().detector.oes.min_size, 40);
  // A file works as a name does.
  const auto file = (cropsight::testing::source_dir() / "models/broccoli-oes-uk.json").string();
  EXPECT_EQ(pl::broccoli::make_pipeline({.model = file})->config().detector.pipeline, uk->config().detector.pipeline);
  EXPECT_NE(error_message([] { pl::broccoli::make_pipeline({.sets = {"no_such_key=1"}}); }).find("no_such_key"),
            std::string::npos);
  EXPECT_NE(error_message([] { pl::broccoli::make_pipeline({.model = "no-such-model"}); }).find("no-such-model"),
            std::string::npos);
}

TEST(MakePipeline, SeedlingTakesAPresetAndSets) {
  const auto fast = pl::seedling::make_pipeline({});
  const auto paper = pl::seedling::make_pipeline({.preset = "seedling-paper"});
  EXPECT_NE(fast->config().gmm.components, 0);
  const auto set = pl::seedling::make_pipeline({.sets = {"gmm.components=3"}});
  EXPECT_EQ(set->config().gmm.components, 3);
  EXPECT_NE(error_message([] { pl::seedling::make_pipeline({.sets = {"gmm.components=-1"}}); }).find("gmm.components"),
            std::string::npos);
  (void)paper;
}

TEST(MakePipeline, PotatoModelIsAnOnnxDetectorByName) {
  const auto classical = pl::potato::spec_config({});
  EXPECT_NE(classical.detector.backend, pl::potato::spec_config({.model = "potato-cnn"}).detector.backend);
  const auto onnx = pl::potato::spec_config({.model = "potato-cnn"});
  EXPECT_NE(onnx.detector.onnx.model.find("potato-cnn.onnx"), std::string::npos) << onnx.detector.onnx.model;
  EXPECT_NE(pl::potato::make_pipeline({.preset = "potato-paper"}), nullptr);
}

// detector.backend resolves a detector named without extension: opencv runs the .onnx; an
// explicit runtime that contradicts a named file is the spec's error.
TEST(MakePipeline, GrapeDetectorBackendPicksTheRuntimeOfANamedModel) {
  const auto pipe = pl::grape::make_pipeline({.sets = {"detector.backend=opencv", "segmenter.threads=1"},
                                              .model = "grape-gbdt-fast",
                                              .detector = "detector-grape"});
  EXPECT_TRUE(pipe->has_detector());
  EXPECT_EQ(pipe->config().detector.backend, cropsight::nn::DetectorRuntime::opencv);
  EXPECT_NE(
      error_message([] {
        pl::grape::make_pipeline(
            {.sets = {"detector.backend=libtorch"}, .model = "grape-gbdt-fast", .detector = "detector-grape.onnx"});
      }).find("runtime is libtorch"),
      std::string::npos);
  EXPECT_NE(error_message([] {
              pl::grape::make_pipeline({.sets = {"detector.backend=tensorrt"}, .model = "grape-gbdt-fast"});
            }).find("auto, libtorch, opencv"),
            std::string::npos);
}

TEST(MakePipeline, GrapeSplitsTheSegmenterSets) {
  const auto pipe = pl::grape::make_pipeline(
      {.sets = {"cut_point.min_points=12", "segmenter.threads=1"}, .model = "grape-gbdt-fast", .threads = 0});
  EXPECT_EQ(pipe->config().cut_point.min_points, 12);
  EXPECT_EQ(pipe->segmenter().config().threads, 1);
  EXPECT_NE(pipe->segmenter().config().model.find("grape-gbdt-fast.json"), std::string::npos);
  EXPECT_FALSE(pipe->has_detector());
  // The pipeline's one config records the segmenter it runs.
  EXPECT_EQ(pipe->config().segmenter.threads, 1);
  EXPECT_EQ(pipe->config().segmenter.model, pipe->segmenter().config().model);
  EXPECT_EQ(pl::grape::segmenter_config({.model = "grape-gbdt-fast", .threads = 3}).threads, 3);
  EXPECT_NE(error_message([] {
              pl::grape::make_pipeline({.sets = {"segmenter.no_such=1"}, .model = "grape-gbdt-fast"});
            }).find("no_such"),
            std::string::npos);
}

}  // namespace pipeline_spec_test
