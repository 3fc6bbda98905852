// The studio's mask wire format: runs round-trip, and a label body of any bytes gives heads
// inside the frame or an error (mutations of valid bodies, as the fuzzer makes them).
#include <gtest/gtest.h>

#include <random>

#include "studio/pixel_runs.hpp"

namespace cropsight::studio {

TEST(PixelRuns, RoundTrip) {
  const std::vector<int> pixels{0, 1, 2, 7, 9, 10, 63};
  EXPECT_EQ(to_runs(pixels), nlohmann::json({0, 3, 7, 1, 9, 2, 63, 1}));
  std::string error;
  EXPECT_EQ(from_runs(to_runs(pixels), 64, error), pixels);
  EXPECT_FALSE(from_runs(nlohmann::json({63, 2}), 64, error));
  EXPECT_FALSE(from_runs(nlohmann::json({0, 0}), 64, error));
  EXPECT_FALSE(from_runs(nlohmann::json({0}), 64, error));
}

TEST(PixelRuns, BoundsTheMasksOfOneBody) {
  std::string error;
  std::string body = "{\"heads\": [";
  for (int k = 0; k < 5; ++k) body += std::string(k ? "," : "") + "[0, 64]";
  EXPECT_FALSE(parse_heads_body(body + "]}", 64, error));
  EXPECT_NE(error.find("four times"), std::string::npos) << error;
  EXPECT_TRUE(parse_heads_body("{\"heads\": [[0, 64], [0, 64]]}", 64, error));
}

TEST(PixelRuns, MutatedBodiesGiveHeadsInsideTheFrameOrAnError) {
  const std::vector<std::string> seeds{R"({"heads": [[0, 5, 64, 5], [100, 3]]})", R"({"heads": []})",
                                       R"({"heads": [[3071, 1]]})"};
  std::mt19937 random(55);
  const std::string alphabet = "{}[]\",:0123456789-e.heads ";
  int accepted = 0;
  for (int k = 0; k < 20000; ++k) {
    std::string body = seeds[random() % seeds.size()];
    for (int m = 1 + int(random() % 4); m > 0 && !body.empty(); --m) {
      const std::size_t at = random() % body.size();
      switch (random() % 3) {
        case 0:
          body[at] = alphabet[random() % alphabet.size()];
          break;
        case 1:
          body.erase(at, 1);
          break;
        default:
          body.insert(at, 1, alphabet[random() % alphabet.size()]);
      }
    }
    std::string error;
    const auto heads = parse_heads_body(body, 64 * 48, error);
    if (!heads) {
      EXPECT_FALSE(error.empty()) << body;
      continue;
    }
    ++accepted;
    for (const auto& head : *heads)
      for (int p : head) ASSERT_TRUE(p >= 0 && p < 64 * 48) << body;
  }
  EXPECT_GT(accepted, 0);
}

}  // namespace cropsight::studio
