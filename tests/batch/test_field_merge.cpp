// The merge of field maps: the temporal filter's association rule applied to maps.
#include "cropsight/batch/field_merge.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>

#include "cropsight/batch/field_outputs.hpp"

namespace cropsight::batch {
namespace field_merge_test {

tracking::TrackedHead head(int id, double x, double y, int frames = 10, double diameter = 120) {
  tracking::TrackedHead h;
  h.id = id;
  h.position = {x, y, 0.4};
  h.frames_seen = frames;
  h.first_frame = 0;
  h.last_frame = frames - 1;
  h.diameter_mm = h.bbox_mm = diameter;
  return h;
}

TEST(FieldMerge, HeadsWithinTheRadiusFuseOthersStay) {
  const MergeRule rule;  // 0.05 m, the filter's default
  const std::vector<PassMap> maps = {{"a", "a", {head(1, 0, 0, 10, 100), head(2, 1, 0)}},
                                     {"b", "b", {head(1, 0.03, 0, 30, 140), head(2, 1.07, 0)}}};
  const auto merged = merge_field_maps(maps, rule);
  ASSERT_EQ(merged.size(), 3u);  // 3 cm apart: one head; 7 cm apart: two
  EXPECT_EQ(merged[0].seen_by.size(), 2u);
  EXPECT_NEAR(merged[0].position.x(), 0.03 * 30 / 40, 1e-12);  // averaged over frames_seen
  EXPECT_NEAR(merged[0].diameter_mm, (100 * 10 + 140 * 30) / 40.0, 1e-9);
  EXPECT_EQ(merged[0].frames_seen, 40);
  EXPECT_TRUE(merged[0].harvestable);
  EXPECT_EQ(merged[1].seen_by.size(), 1u);
  EXPECT_EQ(merged[2].seen_by[0].map, 1u);
}

TEST(FieldMerge, OneToOneClosestPairsFirst) {
  // Two heads of map b both near one merged head: only the closer joins it (as in the filter, two
  // heads closer than the radius stay two heads).
  const std::vector<PassMap> maps = {{"a", "a", {head(1, 0, 0)}}, {"b", "b", {head(1, 0.04, 0), head(2, -0.01, 0)}}};
  const auto merged = merge_field_maps(maps, MergeRule{});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0].seen_by.size(), 2u);
  EXPECT_EQ(merged[0].seen_by[1].head_id, 2);
  EXPECT_EQ(merged[1].seen_by[0].head_id, 1);
}

TEST(FieldMerge, GridFindsPairsAcrossCellBordersAndNegativeCoordinates) {
  // Brute force over random maps: every fused pair within the radius, every merge equal to the
  // one-to-one closest-pairs rule checked pair by pair.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-2.0, 2.0), jitter(-0.03, 0.03);
  std::vector<PassMap> maps(2);
  for (int i = 0; i < 300; ++i) {
    const double x = pos(rng), y = pos(rng);
    maps[0].heads.push_back(head(i + 1, x, y));
    maps[1].heads.push_back(head(i + 1, x + jitter(rng), y + jitter(rng)));
  }
  const auto merged = merge_field_maps(maps, MergeRule{});
  std::set<std::pair<int, int>> fused;  // (head of a, head of b)
  for (const auto& m : merged)
    if (m.seen_by.size() == 2) fused.insert({m.seen_by[0].head_id, m.seen_by[1].head_id});
  // The rule by brute force: every pair within the radius, closest first, each head used once.
  std::vector<std::tuple<double, int, int>> pairs;
  for (const auto& a : maps[0].heads)
    for (const auto& b : maps[1].heads)
      if (const double d = (a.position - b.position).norm(); d <= 0.05) pairs.emplace_back(d, b.id, a.id);
  std::sort(pairs.begin(), pairs.end());
  std::set<int> used_a, used_b;
  std::set<std::pair<int, int>> expected;
  for (const auto& [d, b, a] : pairs)
    if (!used_a.count(a) && !used_b.count(b)) used_a.insert(a), used_b.insert(b), expected.insert({a, b});
  EXPECT_EQ(fused, expected);
  EXPECT_GT(fused.size(), 250u);
  EXPECT_EQ(merged.size(), 600 - fused.size());
}

TEST(FieldMerge, RowsSplitAtGapsAcrossTheRows) {
  const std::vector<PassMap> maps = {
      {"a", "a", {head(1, 0, 0.61), head(2, 1, -0.02), head(3, 2, 0.02), head(4, 3, 0.6)}}};
  auto merged = merge_field_maps(maps, MergeRule{});
  assign_rows(merged, 0.3);
  EXPECT_EQ(merged[0].row, 2);
  EXPECT_EQ(merged[1].row, 1);
  EXPECT_EQ(merged[2].row, 1);
  EXPECT_EQ(merged[3].row, 2);
  const std::string rows = rows_csv(merged, maps);
  EXPECT_NE(rows.find("1,0.000,2,2,1,120.0\n"), std::string::npos) << rows;
}

TEST(FieldMerge, CsvHasBothFramesWhenGeoReferenced) {
  const std::vector<PassMap> maps = {{"a", "a-f000000", {head(7, 10, 0)}}};
  const auto merged = merge_field_maps(maps, MergeRule{});
  const io::GeoReference geo(io::GeoOrigin{52.0, 0.0, 5.0, 90.0});
  const std::string csv = merged_map_csv(merged, maps, &geo);
  EXPECT_NE(csv.find("latitude_deg,longitude_deg,altitude_m"), std::string::npos);
  EXPECT_NE(csv.find(",52.000000000,0.000145"), std::string::npos) << csv;  // 10 m east of 0°
  EXPECT_NE(csv.find("a-f000000#7:0-9"), std::string::npos) << csv;
  EXPECT_EQ(merged_map_csv(merged, maps, nullptr).find("latitude"), std::string::npos);
}

}  // namespace field_merge_test
}  // namespace cropsight::batch
