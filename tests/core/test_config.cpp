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
}
