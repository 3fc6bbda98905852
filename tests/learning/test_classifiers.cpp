#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/learning/classifier.hpp"
#include "cropsight/learning/standardizer.hpp"
#include "learning/knn_classifier.hpp"
#include "learning/svm_classifier.hpp"
#include "learning/temp_file.hpp"
#include "test_learning_common.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::learning;

TEST(Standardizer, FitsMeanAndPopulationStd) {
  Dataset d(2);
  d.add(std::vector<float>{1.0f, 5.0f}, 0);
  d.add(std::vector<float>{3.0f, 5.0f}, 1);
  const Standardizer s = Standardizer::fit(d);
  EXPECT_FLOAT_EQ(s.mean[0], 2.0f);
  EXPECT_FLOAT_EQ(s.std[0], 1.0f);
  EXPECT_FLOAT_EQ(s.mean[1], 5.0f);
  EXPECT_FLOAT_EQ(s.std[1], 1.0f);  // constant feature: std 1, maps to 0
  float z[2];
  const float x[2] = {4.0f, 5.0f};
  s.apply(x, z);
  EXPECT_FLOAT_EQ(z[0], 2.0f);
  EXPECT_FLOAT_EQ(z[1], 0.0f);
}

TEST(Dataset, RejectsBadRows) {
  Dataset d(3);
  EXPECT_THROW(d.add(std::vector<float>{1, 2}, 1), Error);
  EXPECT_THROW(d.add(std::vector<float>{1, 2, NAN}, 1), Error);
  EXPECT_THROW(d.add(std::vector<float>{1, 2, 3}, 2), Error);
  d.add(std::vector<float>{1, 2, 3}, 1);
  EXPECT_EQ(d.size(), 1u);
  EXPECT_EQ(d.positives(), 1u);
}

namespace {
double accuracy(const Classifier& c, const Dataset& d) {
  std::size_t ok = 0;
  for (std::size_t i = 0; i < d.size(); ++i) ok += (c.predict(d.row(i)) ? 1 : 0) == d.labels[i];
  return double(ok) / double(d.size());
}
}  // namespace

// libsvm's model goes through a file: an anonymous in-memory one, so that a process killed while
// it exists (kill safety) leaves nothing in the temporary folder.
TEST(Svm, ItsTemporaryModelFileIsNeverInTheTemporaryFolder) {
  cropsight::testing::TempDir tmp;
  ASSERT_EQ(setenv("TMPDIR", tmp.path().c_str(), 1), 0);
  {
    detail::TempFile file;
    file.write("svm_type c_svc\n");
    EXPECT_TRUE(std::filesystem::is_empty(tmp.path())) << file.path();
    std::ifstream in(file.path());
    std::string line;
    EXPECT_TRUE(std::getline(in, line));
    EXPECT_EQ(line, "svm_type c_svc");
    ClassifierParams p;
    p.type = "svm-rbf";
    const auto clf = train_classifier(testdata::gaussians(60, 4, 1.5, 3), p);  // save, then load
    EXPECT_TRUE(std::filesystem::is_empty(tmp.path()));
  }
  unsetenv("TMPDIR");
}

class SvmKernels : public ::testing::TestWithParam<std::string> {};

// The dense scorer is our hot path: it must give libsvm's own decision value (sign-corrected).
TEST_P(SvmKernels, DenseScoreMatchesLibsvmAndSeparatesClasses) {
  const Dataset raw = testdata::gaussians(600, 24, 1.5, 7);
  const Standardizer s = Standardizer::fit(raw);
  const Dataset train = s.apply(raw);
  const Dataset test = s.apply(testdata::gaussians(400, 24, 1.5, 8));
  ClassifierParams p;
  p.type = GetParam();
  p.linear_c = 0.01;
  const auto clf = train_classifier(train, p);
  const auto& svm = dynamic_cast<const detail::SvmClassifier&>(*clf);
  EXPECT_GT(svm.model_size(), 0u);
  for (std::size_t i = 0; i < test.size(); ++i) {
    const double ref = svm.libsvm_score(test.row(i));
    EXPECT_NEAR(svm.score(test.row(i)), ref, 1e-4 * (1.0 + std::abs(ref))) << "sample " << i;
  }
  // Shift 1.5σ on 12 features: Bayes accuracy is ~1; a working SVM is far above chance (0.7).
  EXPECT_GT(accuracy(*clf, test), 0.95);
}

// The RBF scorer pads rows to 16 floats and z to the stack (heap above 1024): check VFH's 308
// and a dimension past the stack buffer against libsvm too.
TEST(Svm, DenseRbfScoreMatchesLibsvmAtVfhAndLongDimensions) {
  for (int dim : {308, 1100}) {
    const Dataset raw = testdata::gaussians(200, dim, 1.0, 11);
    const Standardizer s = Standardizer::fit(raw);
    const Dataset train = s.apply(raw);
    const Dataset test = s.apply(testdata::gaussians(60, dim, 1.0, 12));
    ClassifierParams p;
    p.type = "svm-rbf";
    p.rbf_gamma = 1.0 / dim;
    const auto clf = train_classifier(train, p);
    const auto& svm = dynamic_cast<const detail::SvmClassifier&>(*clf);
    ASSERT_GT(svm.model_size(), 0u) << dim;
    for (std::size_t i = 0; i < test.size(); ++i) {
      const double ref = svm.libsvm_score(test.row(i));
      EXPECT_NEAR(svm.score(test.row(i)), ref, 1e-4 * (1.0 + std::abs(ref))) << "dim " << dim << " sample " << i;
      EXPECT_NEAR(svm.baseline_score(test.row(i)), ref, 1e-4 * (1.0 + std::abs(ref)))
          << "dim " << dim << " sample " << i;
    }
  }
}

// score_rows (support vectors in blocks, two of them by two vectors per step) must give score()'s
// bits for every row, for odd and even row counts, block tails and both kernels' layouts; the
// KNN and linear kernels use the default loop.
TEST(Svm, ScoreRowsIsBitIdenticalToScorePerRow) {
  for (int dim : {24, 308}) {
    Dataset train = testdata::gaussians(300, dim, 1.0, 31);
    for (std::size_t i = 0; i < train.size(); ++i)
      for (int j = dim / 2; j < dim; j += 3) train.values[i * std::size_t(dim) + std::size_t(j)] = 0.0f;
    const Dataset test = testdata::gaussians(67, dim, 1.0, 32);
    for (const char* type : {"svm-rbf", "svm-linear", "knn"}) {
      ClassifierParams p;
      p.type = type;
      p.rbf_gamma = 1.0 / dim;
      const auto clf = train_classifier(train, p);
      for (std::size_t rows : {std::size_t(0), std::size_t(1), std::size_t(2), std::size_t(33), test.size()}) {
        std::vector<float> out(rows, -1.0f);
        clf->score_rows(test.values.data(), rows, out.data());
        for (std::size_t r = 0; r < rows; ++r)
          ASSERT_EQ(out[r], clf->score(test.row(r))) << type << " dim " << dim << " rows " << rows << " row " << r;
      }
    }
  }
}

// The RBF scorer drops the columns that are 0 in every support vector from its dot products
// (VFH bins no training cluster fills): a test vector that is non-zero there must still get
// libsvm's value (those columns count in |sv − z|² through |z|²).
TEST(Svm, DenseRbfScoreMatchesLibsvmWhenTrainingLeavesColumnsEmpty) {
  const int dim = 308;
  Dataset train = testdata::gaussians(200, dim, 1.0, 21);
  for (std::size_t i = 0; i < train.size(); ++i)
    for (int j = 100; j < 250; ++j) train.values[i * dim + std::size_t(j)] = 0.0f;
  const Dataset test = testdata::gaussians(60, dim, 1.0, 22);  // non-zero in 100..249
  ClassifierParams p;
  p.type = "svm-rbf";
  p.rbf_gamma = 1.0 / dim;
  const auto clf = train_classifier(train, p);
  const auto& svm = dynamic_cast<const detail::SvmClassifier&>(*clf);
  ASSERT_GT(svm.model_size(), 0u);
  for (std::size_t i = 0; i < test.size(); ++i) {
    const double ref = svm.libsvm_score(test.row(i));
    EXPECT_NEAR(svm.score(test.row(i)), ref, 1e-4 * (1.0 + std::abs(ref))) << "sample " << i;
    EXPECT_NEAR(svm.baseline_score(test.row(i)), ref, 1e-4 * (1.0 + std::abs(ref))) << "sample " << i;
  }
}

// Whichever class libsvm sees first, a positive score must mean the positive class.
TEST_P(SvmKernels, ScoreSignDoesNotDependOnSampleOrder) {
  Dataset raw = testdata::gaussians(300, 10, 2.0, 3);
  for (int first_label : {0, 1}) {
    Dataset ordered(raw.dim);
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t i = 0; i < raw.size(); ++i)
        if ((raw.labels[i] == first_label) == (pass == 0)) ordered.add(raw.row_span(i), raw.labels[i]);
    const Standardizer s = Standardizer::fit(ordered);
    const Dataset d = s.apply(ordered);
    ClassifierParams p;
    p.type = GetParam();
    const auto clf = train_classifier(d, p);
    double mean_pos = 0, mean_neg = 0;
    for (std::size_t i = 0; i < d.size(); ++i) (d.labels[i] ? mean_pos : mean_neg) += clf->score(d.row(i));
    EXPECT_GT(mean_pos / double(d.positives()), 0.0) << "first label " << first_label;
    EXPECT_LT(mean_neg / double(d.negatives()), 0.0) << "first label " << first_label;
  }
}

INSTANTIATE_TEST_SUITE_P(Learning, SvmKernels, ::testing::Values("svm-rbf", "svm-linear"));

TEST(Svm, BalancedWeightsRaiseMinorityRecall) {
  // 10 % positives with a weak signal: unweighted SVMs favour the majority class.
  const Dataset raw = testdata::gaussians(800, 10, 0.8, 11, 0.1);
  const Standardizer s = Standardizer::fit(raw);
  const Dataset d = s.apply(raw);
  auto recall = [&](bool balanced) {
    ClassifierParams p;
    p.type = "svm-linear";
    p.linear_c = 0.05;
    p.balanced_weights = balanced;
    const auto clf = train_classifier(d, p);
    std::size_t tp = 0;
    for (std::size_t i = 0; i < d.size(); ++i) tp += d.labels[i] && clf->predict(d.row(i));
    return double(tp) / double(d.positives());
  };
  EXPECT_GT(recall(true), recall(false) + 0.1);
}

TEST(Knn, ScoreIsFractionOfPositiveNeighboursAndMatchesBruteForce) {
  const Dataset raw = testdata::gaussians(500, 16, 1.5, 5);
  const Standardizer s = Standardizer::fit(raw);
  const Dataset train = s.apply(raw);
  const Dataset test = s.apply(testdata::gaussians(200, 16, 1.5, 6));
  ClassifierParams p;
  p.type = "knn";
  const auto clf = train_classifier(train, p);
  const auto& knn = dynamic_cast<const detail::KnnClassifier&>(*clf);
  for (std::size_t i = 0; i < test.size(); ++i) {
    const float sc = knn.score(test.row(i));
    EXPECT_FLOAT_EQ(sc, knn.brute_force_score(test.row(i))) << "sample " << i;
    EXPECT_FLOAT_EQ(sc * 11.0f, std::round(sc * 11.0f));  // k = 11 neighbours
  }
  EXPECT_GT(accuracy(*clf, test), 0.9);
}

TEST(Classifier, RejectsBadInput) {
  Dataset one_class(3);
  one_class.add(std::vector<float>{1, 2, 3}, 1);
  one_class.add(std::vector<float>{1, 2, 4}, 1);
  ClassifierParams p;
  EXPECT_THROW(train_classifier(one_class, p), Error);
  p.type = "knn";
  EXPECT_THROW(train_classifier(one_class, p), Error);
  p.type = "forest";
  EXPECT_THROW(train_classifier(one_class, p), Error);
  p.type = "svm-rbf";
  p.rbf_gamma = -1;
  EXPECT_THROW(p.validate("test"), Error);
}
