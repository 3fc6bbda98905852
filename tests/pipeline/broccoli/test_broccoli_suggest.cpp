// Which frames to label next (pipeline/broccoli/suggest.hpp): the candidate weights, the depth
// descriptor, the greedy ranking's uncertainty and diversity terms, and the whole ranking over a
// simulated sequence with the shipped general model.
#include "cropsight/pipeline/broccoli/suggest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "pipeline/broccoli/broccoli_sim_frames.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
namespace bs = cropsight::pipeline::broccoli;

namespace suggest_test {

bs::Candidate scored(float score, bool described = true, bool proposed = false) {
  bs::Candidate c;
  c.score = score;
  c.described = described;
  c.proposed = proposed;
  return c;
}

RgbdFrame flat_frame(std::uint16_t raw_depth) {
  RgbdFrame f;
  f.camera.depth_scale = 0.001;
  f.depth = DepthImage(8, 6, raw_depth);
  return f;
}

// A frame whose descriptor is all in one bin (`bin` of 4), so that frames in different bins lie
// at distance 1 and frames in the same bin at 0.
bs::FrameUncertainty synthetic(int index, double uncertainty, int bin) {
  bs::FrameUncertainty u;
  u.frame = index;
  u.uncertainty = uncertainty;
  u.descriptor.assign(4, 0.0f);
  u.descriptor[std::size_t(bin)] = 1.0f;
  return u;
}

std::vector<int> ranked_indices(const std::vector<bs::SuggestedFrame>& ranked) {
  std::vector<int> out;
  for (const auto& r : ranked) out.push_back(r.frame);
  return out;
}

}  // namespace suggest_test

using namespace suggest_test;

TEST(BroccoliSuggest, CandidateWeightsFallWithDistanceFromTheThreshold) {
  bs::SuggestConfig cfg;
  cfg.score_scale = 0.5f;
  const std::vector<bs::Candidate> cands{scored(0.4f), scored(0.9f), scored(-3.0f, /*described=*/false),
                                         scored(0.4f, true, /*proposed=*/true)};
  const auto u = bs::measure_frame(7, flat_frame(1000), cands, 0.4f, cfg);
  EXPECT_EQ(u.frame, 7);
  EXPECT_EQ(u.candidates, 2) << "neither the undescribed cluster nor the CNN's proposal is the model's doubt";
  EXPECT_EQ(u.doubtful, 2);
  EXPECT_NEAR(u.max_weight, 1.0, 1e-9);
  EXPECT_NEAR(u.uncertainty, 1.0 + std::exp(-1.0), 1e-6);
  EXPECT_EQ(u.heads, 2) << "0.4 and 0.9 lie at or above the threshold 0.4; the others are not the model's";
  const std::vector<bs::Candidate> below{scored(0.39f), scored(-1.0f)};
  EXPECT_EQ(bs::measure_frame(0, flat_frame(1000), below, 0.4f, cfg).heads, 0);
}

TEST(BroccoliSuggest, DepthDescriptorIsANormalisedHistogram) {
  bs::SuggestConfig cfg;  // 24 bins over 0.3-2.0 m
  const auto u = bs::measure_frame(0, flat_frame(1000), {}, 0.0f, cfg);
  ASSERT_EQ(u.descriptor.size(), 24u);
  EXPECT_NEAR(std::accumulate(u.descriptor.begin(), u.descriptor.end(), 0.0), 1.0, 1e-6);
  const std::size_t bin = std::size_t((1.0 - 0.3) / (1.7 / 24));
  EXPECT_NEAR(u.descriptor[bin], 1.0, 1e-6) << "every pixel at 1.0 m";
  const auto empty = bs::measure_frame(0, flat_frame(0), {}, 0.0f, cfg);
  EXPECT_EQ(std::accumulate(empty.descriptor.begin(), empty.descriptor.end(), 0.0), 0.0) << "no return, no mass";
}

TEST(BroccoliSuggest, WithoutDiversityTheMostUncertainFramesComeFirst) {
  std::vector<bs::FrameUncertainty> frames;
  const double u[] = {0.2, 0.9, 0.5, 0.9, 0.1};
  for (int i = 0; i < 5; ++i) frames.push_back(synthetic(i, u[i], i % 4));
  bs::SuggestConfig cfg;
  cfg.frames = 5;
  cfg.diversity_weight = 0.0;
  const auto ranked = bs::rank_frames(frames, cfg);
  EXPECT_EQ(ranked_indices(ranked), (std::vector<int>{1, 3, 2, 0, 4})) << "ties go to the lower index";
  for (std::size_t k = 1; k < ranked.size(); ++k) EXPECT_LE(ranked[k].gain, ranked[k - 1].gain);
}

TEST(BroccoliSuggest, NeighboursOfAChosenFrameGiveWayToAFrameElsewhere) {
  std::vector<bs::FrameUncertainty> frames;
  for (int i = 0; i < 20; ++i) frames.push_back(synthetic(i, 0.1, i % 4));
  frames[10].uncertainty = 1.0;
  frames[11].uncertainty = 0.95;  // the next view of the same heads
  frames[3].uncertainty = 0.6;    // less doubtful, but another part of the pass
  bs::SuggestConfig cfg;
  cfg.frames = 2;
  cfg.diversity_weight = 0.0;
  EXPECT_EQ(ranked_indices(bs::rank_frames(frames, cfg)), (std::vector<int>{10, 11}));
  cfg.diversity_weight = 0.8;
  EXPECT_EQ(ranked_indices(bs::rank_frames(frames, cfg)), (std::vector<int>{10, 3}));
}

TEST(BroccoliSuggest, AFarFrameThatLooksTheSameGivesWayToADifferentView) {
  // Frames 0 and 30 share a depth histogram; 60 looks different. Far apart in index, so only the
  // descriptor tells 30 from 60.
  const std::vector<bs::FrameUncertainty> frames{synthetic(0, 1.0, 0), synthetic(30, 0.9, 0), synthetic(60, 0.8, 1)};
  bs::SuggestConfig cfg;
  cfg.frames = 10;  // more than there are: all three, once each
  const auto ranked = ranked_indices(bs::rank_frames(frames, cfg));
  EXPECT_EQ(ranked, (std::vector<int>{0, 60, 30}));
}

// Frames equally doubtful and equally far apart: without the heads term the ranking keeps index
// order; with it the frames the model sees most heads in come first, and the term adds to the
// uncertainty rather than replacing it (the most doubtful frame, without heads, still comes before
// less doubtful frames with one or two).
TEST(BroccoliSuggest, FramesWithMoreHeadsComeFirstWhenHeadsWeigh) {
  std::vector<bs::FrameUncertainty> frames;
  const int heads[] = {1, 4, 0, 2};
  for (int i = 0; i < 4; ++i) {
    frames.push_back(synthetic(i * 20, 0.5, i));
    frames.back().heads = heads[i];
  }
  bs::SuggestConfig cfg;
  cfg.frames = 4;
  cfg.heads_weight = 0.0;
  EXPECT_EQ(ranked_indices(bs::rank_frames(frames, cfg)), (std::vector<int>{0, 20, 40, 60}));
  cfg.heads_weight = 1.0;
  const auto ranked = bs::rank_frames(frames, cfg);
  EXPECT_EQ(ranked_indices(ranked), (std::vector<int>{20, 60, 0, 40}));
  EXPECT_NEAR(ranked.front().gain, (cfg.floor + 1.0 + 1.0), 1e-9) << "full uncertainty and the most heads";
  frames[2].uncertainty = 1.0;  // now the most doubtful frame, still without heads
  frames[3].uncertainty = 0.0;
  cfg.frames = 2;
  EXPECT_EQ(ranked_indices(bs::rank_frames(frames, cfg)), (std::vector<int>{20, 40}));
}

TEST(BroccoliSuggest, BadSettingsAreRefused) {
  bs::SuggestConfig cfg;
  cfg.frames = 0;
  EXPECT_THROW(cfg.validate("test"), Error);
  cfg = {};
  cfg.diversity_weight = 1.5;
  EXPECT_THROW(cfg.validate("test"), Error);
  cfg = {};
  cfg.heads_weight = -0.1;
  EXPECT_THROW(cfg.validate("test"), Error);
  cfg = {};
  cfg.score_scale = 0.0f;
  EXPECT_THROW(bs::rank_frames({synthetic(0, 1.0, 0)}, cfg), Error);
}

// The whole ranking on a simulated wide field with the shipped general model: distinct frames of
// the sequence, the frame with the most doubt and heads first, and the same ranking whether or not
// the sequence carries labels (suggest never reads them).
TEST(BroccoliSuggest, RanksASequenceWithTheGeneralModelIgnoringItsLabels) {
  const auto frames = testdata::simulate(testdata::sim_preset("random-wide"), 6111, 10);
  cropsight::testing::TempDir tmp;
  for (const bool labels : {true, false}) {
    io::SequenceWriter w(tmp / (labels ? "labelled" : "bare"), frames[0].camera);
    for (RgbdFrame f : frames) {
      if (!labels) f.labels = {};
      w.write(f);
    }
    w.finish();
  }
  const auto model = (cropsight::testing::source_dir() / "models" / "broccoli-oes-general.json").string();
  auto pipe = bs::make_pipeline({.sets = {"track=false"}, .model = model});
  bs::SuggestConfig cfg;
  cfg.frames = 4;
  int calls = 0;
  const auto ranked = bs::suggest_frames(*pipe, io::SequenceReader(tmp / "labelled"), cfg, [&](int done, int total) {
    EXPECT_EQ(total, 10);
    EXPECT_EQ(done, ++calls);
  });
  EXPECT_EQ(calls, 10);
  ASSERT_EQ(ranked.size(), 4u);
  const std::vector<int> order = ranked_indices(ranked);
  EXPECT_EQ(std::set<int>(order.begin(), order.end()).size(), 4u);
  for (int f : order) EXPECT_TRUE(f >= 0 && f < 10);
  cfg.frames = 4;
  EXPECT_EQ(ranked_indices(bs::suggest_frames(*pipe, io::SequenceReader(tmp / "bare"), cfg)), order);
  // Uncertainty alone (no heads term, no diversity): frames in falling order of doubt.
  cfg.frames = 10;
  cfg.diversity_weight = 0.0;
  cfg.heads_weight = 0.0;
  const auto all = bs::suggest_frames(*pipe, io::SequenceReader(tmp / "bare"), cfg);
  EXPECT_GT(all.front().measured.candidates, 0);
  for (std::size_t k = 1; k < all.size(); ++k) EXPECT_LE(all[k].measured.uncertainty, all[k - 1].measured.uncertainty);
  // The first choice of the full rule has the largest doubt-plus-heads term (nothing chosen yet).
  double top_u = 0.0;
  int top_h = 0;
  for (const auto& f : all) top_u = std::max(top_u, f.measured.uncertainty), top_h = std::max(top_h, f.measured.heads);
  auto term = [&](const bs::FrameUncertainty& m) {
    return m.uncertainty / top_u + (top_h > 0 ? double(m.heads) / top_h : 0.0);
  };
  for (const auto& f : all) EXPECT_LE(term(f.measured), term(ranked.front().measured) + 1e-9) << "frame " << f.frame;
}
