#include <gtest/gtest.h>

#include "cropsight/core/config.hpp"
#include "cropsight/core/timer.hpp"

using namespace cropsight;

namespace {
struct Inner {
  double tolerance = 0.02;
  template <class V>
  void visit(V& v) {
    v("tolerance", tolerance, "m");
  }
};
struct Outer {
  int k = 100;
  bool flag = false;
  std::string name = "oes";
  std::vector<double> list{1, 2};
  Inner inner;
  template <class V>
  void visit(V& v) {
    v("k", k, "neighbours");
    v("flag", flag, "");
    v("name", name, "");
    v("list", list, "");
    v("inner", inner, "");
  }
};
}  // namespace

TEST(Config, AppliesNestedValues) {
  Outer o;
  apply_config(o, {{"k", "7"}, {"inner.tolerance", "0.5"}, {"flag", "true"}, {"list", "[3, 4.5]"}}, "test");
  EXPECT_EQ(o.k, 7);
  EXPECT_DOUBLE_EQ(o.inner.tolerance, 0.5);
  EXPECT_TRUE(o.flag);
  EXPECT_EQ(o.list, (std::vector<double>{3, 4.5}));
}

TEST(Config, UnknownKeyAndBadValueAreErrors) {
  Outer o;
  EXPECT_THROW(apply_config(o, {{"kk", "7"}}, "test"), Error);
  EXPECT_THROW(apply_config(o, {{"k", "seven"}}, "test"), Error);
  EXPECT_THROW(apply_config(o, {{"inner.tolerance", "nan"}}, "test"), Error);
  EXPECT_THROW(apply_config(o, {{"flag", "maybe"}}, "test"), Error);
}

TEST(Config, PrefixSelectsSection) {
  Outer o;
  apply_config(o, {{"det.k", "3"}, {"other.x", "1"}}, "test", "det.");
  EXPECT_EQ(o.k, 3);
}

TEST(Config, DumpListsEveryField) {
  const auto d = dump_config(Outer{});
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(std::get<0>(d[4]), "inner.tolerance");
  EXPECT_EQ(std::get<1>(d[0]), "100");
}

TEST(Config, ParseAssignment) {
  EXPECT_EQ(parse_assignment("a.b = 3").first, "a.b");
  EXPECT_EQ(parse_assignment("a.b = 3").second, "3");
  EXPECT_THROW(parse_assignment("novalue"), Error);
}

TEST(StageTimer, Accumulates) {
  StageTimer t;
  t.add("a", 1.0);
  t.add("b", 2.0);
  t.add("a", 3.0);
  ASSERT_EQ(t.stages().size(), 2u);
  EXPECT_DOUBLE_EQ(t.stages()[0].total_ms, 4.0);
  EXPECT_EQ(t.stages()[0].count, 2);
  EXPECT_DOUBLE_EQ(t.total_ms(), 6.0);
  EXPECT_DOUBLE_EQ(t.ms("b"), 2.0);
  EXPECT_DOUBLE_EQ(t.ms("none"), 0.0);
}

TEST(StageTimer, SinceGivesOnlyWhatRanAfterTheCopy) {
  StageTimer t;
  t.add("a", 1.0);
  t.add("b", 2.0);
  const std::vector<StageTimer::Stage> before = t.stages();
  t.add("a", 0.5);
  t.add("c", 4.0);
  const StageTimer frame = t.since(before);
  ASSERT_EQ(frame.stages().size(), 2u);  // b did not run again
  EXPECT_EQ(frame.stages()[0].name, "a");
  EXPECT_DOUBLE_EQ(frame.stages()[0].total_ms, 0.5);
  EXPECT_EQ(frame.stages()[0].count, 1);
  EXPECT_EQ(frame.stages()[1].name, "c");
  EXPECT_DOUBLE_EQ(frame.total_ms(), 4.5);
}

namespace enum_test {
enum class Variant { oes, org, fec };
constexpr std::array<const char*, 3> config_names(Variant) { return {"oes", "org", "fec"}; }
struct WithEnum {
  Variant variant = Variant::oes;
  template <class V>
  void visit(V& v) {
    v("variant", variant, "oes | org | fec");
  }
};
}  // namespace enum_test

TEST(Config, EnumFieldsParseAndDumpTheirSpellings) {
  enum_test::WithEnum c;
  apply_config(c, {{"variant", "fec"}}, "preset.yaml");
  EXPECT_EQ(c.variant, enum_test::Variant::fec);
  const auto dump = dump_config(c);
  ASSERT_EQ(dump.size(), 1u);
  EXPECT_EQ(std::get<1>(dump[0]), "fec");
  try {
    apply_config(c, {{"variant", "kmeans"}}, "preset.yaml");
    FAIL() << "an unknown spelling must throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("preset.yaml"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("oes, org, fec"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("kmeans"), std::string::npos);
  }
  EXPECT_EQ(c.variant, enum_test::Variant::fec);  // unchanged by the failed parse
}

namespace range_test {
struct WithRanges {
  int min_points = 20;
  double fraction = 0.5;
  double offset = 0.0;
  template <class V>
  void visit(V& v) {
    v("min_points", min_points, "points", Range::at_least(1));
    v("fraction", fraction, "share", Range::within(0, 1).open_below());
    v("offset", offset, "mm", Range{});
  }
};
}  // namespace range_test

TEST(Config, RangesDeclaredWithTheFieldAreCheckedOnApplyAndOnDemand) {
  range_test::WithRanges c;
  apply_config(c, {{"min_points", "1"}, {"fraction", "1"}}, "p.yaml");  // both ends that are inside
  EXPECT_EQ(c.min_points, 1);
  auto message = [&](const ConfigMap& m) {
    try {
      range_test::WithRanges d;
      apply_config(d, m, "p.yaml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({{"min_points", "0"}}), "p.yaml: 'min_points' must be at least 1, got 0");
  EXPECT_EQ(message({{"fraction", "0"}}), "p.yaml: 'fraction' must be greater than 0, got 0");
  // check_config sees values set in code too, with a key prefix.
  c.fraction = 1.5;
  try {
    check_config(c, "sizing", "sizing.");
    FAIL() << "fraction 1.5 passed";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "sizing: 'sizing.fraction' must be at most 1, got 1.5");
  }
  c.fraction = 0.5;
  c.offset = std::numeric_limits<double>::infinity();
  EXPECT_THROW(check_config(c, "sizing"), Error);  // Range{}: finite
  // The documentation dump carries the rule.
  const auto dump = dump_config(range_test::WithRanges{});
  EXPECT_EQ(std::get<2>(dump[0]), "points (at least 1)");
}
