#include <gtest/gtest.h>

#include <fstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/learning/model.hpp"
#include "test_learning_common.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::learning;

namespace {
ModelInfo broccoli_info() {
  ModelInfo info;
  info.task = "broccoli-heads";
  info.pipeline = "oes";
  info.features = {"vfh", "va"};
  info.config = {{"normals.normal_smoothing_size", "10"}, {"oes.min_size", "500"}};
  info.provenance = {{"data", "unit test"}};
  return info;
}
}  // namespace

class ModelRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(ModelRoundTrip, TrainSaveLoadGivesIdenticalScores) {
  const Dataset train = testdata::gaussians(300, 20, 1.2, 31);
  const Dataset test = testdata::gaussians(100, 20, 1.2, 32);
  ClassifierParams p;
  p.type = GetParam();
  p.rbf_c = 4.0;  // non-default, must survive the round trip
  const Model m = train_model(train, p, broccoli_info());
  cropsight::testing::TempDir tmp;
  save_model(tmp / "m.json", m);
  const Model back = load_model(tmp / "m.json");
  EXPECT_EQ(back.info.task, "broccoli-heads");
  EXPECT_EQ(back.info.pipeline, "oes");
  EXPECT_EQ(back.info.features, (std::vector<std::string>{"vfh", "va"}));
  EXPECT_EQ(back.info.feature_dim, 20);
  EXPECT_EQ(back.info.config, m.info.config);
  EXPECT_EQ(back.info.provenance.at("data"), "unit test");
  EXPECT_EQ(back.params.type, GetParam());
  EXPECT_DOUBLE_EQ(back.params.rbf_c, 4.0);
  EXPECT_EQ(back.standardizer.mean, m.standardizer.mean);
  EXPECT_EQ(back.standardizer.std, m.standardizer.std);
  std::vector<float> s1, s2;
  int positive = 0;
  for (std::size_t i = 0; i < test.size(); ++i) {
    const float a = m.score(test.row_span(i), s1), b = back.score(test.row_span(i), s2);
    EXPECT_EQ(a, b) << "sample " << i;
    positive += a > m.threshold();
  }
  EXPECT_GT(positive, 0);  // the scores are not degenerate
  EXPECT_LT(positive, int(test.size()));
}

INSTANTIATE_TEST_SUITE_P(Learning, ModelRoundTrip, ::testing::Values("svm-rbf", "svm-linear", "knn"));

TEST(ModelFile, MismatchingPipelineOrFeaturesIsAClearError) {
  ModelInfo info = broccoli_info();
  info.feature_dim = 320;
  EXPECT_NO_THROW(require_compatible(info, "broccoli-heads", "oes", {"vfh", "va"}, 320, "m.json"));
  try {
    require_compatible(info, "broccoli-heads", "fec", {"vfh", "va"}, 320, "m.json");
    FAIL() << "no error for a pipeline mismatch";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "m.json");
    EXPECT_NE(e.problem().find("pipeline 'oes'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(require_compatible(info, "broccoli-heads", "oes", {"vfh"}, 308, "m.json"), Error);
  EXPECT_THROW(require_compatible(info, "broccoli-heads", "oes", {"va", "vfh"}, 320, "m.json"), Error);
  EXPECT_THROW(require_compatible(info, "grape", "oes", {"vfh", "va"}, 320, "m.json"), Error);
}

TEST(ModelFile, BadFilesNameTheFileAndTheProblem) {
  cropsight::testing::TempDir tmp;
  EXPECT_THROW(load_model(tmp / "missing.json"), Error);
  io::write_file_atomic(tmp / "bad.json", "{not json");
  EXPECT_THROW(load_model(tmp / "bad.json"), Error);
  io::write_file_atomic(tmp / "other.json", R"({"format": "something-else"})");
  EXPECT_THROW(load_model(tmp / "other.json"), Error);

  const Model m = train_model(testdata::gaussians(100, 6, 2.0, 33), ClassifierParams{}, broccoli_info());
  save_model(tmp / "good.json", m);
  std::string text = io::read_file(tmp / "good.json");
  // Corrupt the embedded libsvm model: its kernel no longer matches the declared type.
  auto corrupt = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto pos = t.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    t.replace(pos, from.size(), to);
    io::write_file_atomic(tmp / "corrupt.json", t);
    try {
      load_model(tmp / "corrupt.json");
      ADD_FAILURE() << "no error after replacing " << from;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), (tmp / "corrupt.json").string());
    }
  };
  corrupt("kernel_type rbf", "kernel_type linear");
  corrupt("\"feature_dim\": 6", "\"feature_dim\": 7");
  corrupt("\"type\": \"svm-rbf\"", "\"type\": \"tree\"");
  corrupt("\"version\": 1", "\"version\": 9");
  // libsvm would load these: a support vector line dropped (the rest read stale memory), the
  // header's count raised, a number no double holds.
  const auto sv = text.find("\\nSV\\n");
  ASSERT_NE(sv, std::string::npos);
  const auto line_end = text.find("\\n", sv + 6);
  corrupt(text.substr(sv, line_end - sv), "\\nSV");
  corrupt("total_sv ", "total_sv 1");
  // Fuzzing finding 26: libsvm leaves label / rho / nSV null when their header line is missing; a
  // missing label line was a null dereference (SIGSEGV outside the sanitizers).
  for (const char* key : {"\\nlabel ", "\\nrho ", "\\nnr_sv "}) {
    const auto at = text.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    corrupt(text.substr(at, text.find("\\n", at + 2) - at), "");
  }
  // Fuzzing finding 28: libsvm sizes its per-class arrays from nr_class as written (a huge one
  // was a 16-exabyte allocation); the header is now checked line by line before libsvm reads it.
  corrupt("nr_class 2", "nr_class -1234567890");
  corrupt("nr_class 2", "nr_class 3");
  corrupt("\\nnr_sv ", "\\nnr_sv 1000 ");
  corrupt("\\nSV\\n", "\\nlabel 1 -1\\nSV\\n");  // a line twice
  corrupt("\\nSV\\n", "\\nweird 1\\nSV\\n");     // an unknown line
  corrupt("svm_type c_svc", "svm_type nu_svc");
  corrupt("\"mean\": [", "\"mean\": [1e999, ");
  corrupt("\"classifier_model_size\": ", "\"classifier_model_size\": 1");
  // Fuzzing finding 24: a floating-point value where an integer belongs (2e119 as feature_dim) was
  // cast to int by nlohmann's get<int>(), undefined behaviour; a negative size wrapped around.
  corrupt("\"feature_dim\": 6", "\"feature_dim\": 2e119");
  corrupt("\"feature_dim\": 6", "\"feature_dim\": 6.0");
  corrupt("\"version\": 1", "\"version\": 1e30");
  corrupt("\"classifier_model_size\": ", "\"classifier_model_size\": -1");
  corrupt("\"classifier_model_size\": ", "\"classifier_model_size\": 1e300");
}
