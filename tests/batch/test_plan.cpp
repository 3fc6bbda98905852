// The shard plan's seam rule and plan.json.
#include "cropsight/batch/plan.hpp"

#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "testing/testing.hpp"

namespace cropsight::batch {
namespace plan_test {

TEST(ShardPlan, WholeRecordingWhenShortOrUnsplit) {
  const auto one = plan_recording("/data/row-01", 120, {0, 30});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].name, "row-01");
  EXPECT_EQ(one[0].first_frame, 0);
  EXPECT_EQ(one[0].end_frame, 120);
  EXPECT_EQ(plan_recording("/data/row-01", 100, {100, 30}).size(), 1u);
}

TEST(ShardPlan, RangesOwnDisjointFramesAndProcessTheOverlap) {
  const auto shards = plan_recording("/data/long", 250, {100, 30});
  ASSERT_EQ(shards.size(), 3u);
  EXPECT_EQ(shards[0].name, "long-f000000");
  EXPECT_EQ(shards[2].name, "long-f000200");
  int owned = 0;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const Shard& s = shards[k];
    EXPECT_EQ(s.pass, "long");
    EXPECT_EQ(s.own_first, int(k) * 100);
    EXPECT_EQ(s.first_frame, std::max(0, s.own_first - 30));  // leading overlap, clipped
    EXPECT_EQ(s.end_frame, std::min(250, s.own_end + 30));    // trailing overlap, clipped
    owned += s.own_end - s.own_first;
    if (k > 0) {
      EXPECT_EQ(s.own_first, shards[k - 1].own_end);  // owned ranges tile the recording
    }
  }
  EXPECT_EQ(owned, 250);
}

TEST(ShardPlan, JsonRoundTrip) {
  BatchPlan p;
  p.manifest = "/m.yaml";
  p.crop = "broccoli";
  p.spec.model = "/models/x.json";
  p.spec.sets = {"tracking.use_poses=true"};
  p.merge = {0.04, 90, 170};
  p.slurm.partition = "short";
  p.slurm.max_parallel = 3;
  p.shards = plan_recording("/data/long", 250, {100, 30});
  cropsight::testing::TempDir tmp;
  io::write_file_atomic(tmp / "plan.json", plan_json(p));
  const BatchPlan r = read_plan(tmp / "plan.json");
  EXPECT_EQ(plan_json(r), plan_json(p));
  EXPECT_EQ(r.shards[1].own_first, 100);
  EXPECT_EQ(r.merge.association_radius_m, 0.04);
  io::write_file_atomic(tmp / "bad.json", "{\"crop\": 1}");
  EXPECT_THROW(read_plan(tmp / "bad.json"), Error);
}

}  // namespace plan_test
}  // namespace cropsight::batch
