#include <gtest/gtest.h>

#include <limits>

#include "cropsight/core/config.hpp"

using namespace cropsight;

namespace {
struct RangeInner {
  double weight = 0.5;
  template <class V>
  void visit(V& v) {
    v("weight", weight, "share", Range::within(0, 1));
  }
};
struct Ranged {
  int k = 4;
  bool flag = false;
  RangeInner inner;
  template <class V>
  void visit(V& v) {
    v("k", k, "count", Range::at_least(1, "one voter at least"));
    v("flag", flag, "");
    v("inner", inner, "");
  }
};

struct Window {
  int side = 5;
  template <class V>
  void visit(V& v) {
    v("side", side, "px", Range::within(1, 31).odd());
  }
};

std::string check_error(const Ranged& r) {
  try {
    check_config(r, "preset.yaml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ConfigRange, ChecksEachDeclaredFieldWithItsKeyAndReason) {
  Ranged r;
  EXPECT_EQ(check_error(r), "");
  r.k = 0;
  EXPECT_EQ(check_error(r), "preset.yaml: 'k' must be at least 1 (one voter at least), got 0");
  r.k = 1;  // the bound itself is inside
  EXPECT_EQ(check_error(r), "");
  r.inner.weight = 1.5;
  EXPECT_EQ(check_error(r), "preset.yaml: 'inner.weight' must be at most 1, got 1.5");
  r.inner.weight = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(check_error(r).find("'inner.weight' must be finite"), std::string::npos);
  r.inner.weight = std::numeric_limits<double>::infinity();
  EXPECT_NE(check_error(r).find("'inner.weight' must be finite"), std::string::npos);
}

TEST(ConfigRange, RangedFieldsStillApplyAndDump) {
  Ranged r;
  apply_config(r, {{"k", "7"}, {"inner.weight", "0.25"}}, "test");
  EXPECT_EQ(r.k, 7);
  EXPECT_DOUBLE_EQ(r.inner.weight, 0.25);
  const auto d = dump_config(r);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(std::get<0>(d[2]), "inner.weight");
  EXPECT_EQ(std::get<1>(d[0]), "7");
  EXPECT_THROW(apply_config(r, {{"k", "seven"}}, "test"), Error);
}

TEST(ConfigRange, OddAndMultipleOfRulesForIntegerFields) {
  const Range odd = Range::within(1, 9).odd();
  EXPECT_EQ(odd.violation(5), "");
  EXPECT_EQ(odd.violation(4), "must be odd");
  EXPECT_EQ(odd.violation(11), "must be at most 9");  // the bounds are checked first
  EXPECT_EQ(odd.rule(), "odd, in [1, 9]");
  const Range sixteen = Range::within(16, 1024).multiple_of(16);
  EXPECT_EQ(sixteen.violation(64), "");
  EXPECT_EQ(sixteen.violation(20), "must be a multiple of 16");
  EXPECT_EQ(sixteen.violation(0), "must be at least 16");
  // The step rule survives the open-end modifiers, in either order.
  EXPECT_EQ(Range::within(0, 9).odd().open_below().violation(2), "must be odd");
  EXPECT_EQ(Range::within(0, 9).open_below().odd().violation(0), "must be greater than 0");
  Window w;
  try {
    apply_config(w, {{"side", "6"}}, "p.yaml");
    ADD_FAILURE() << "an even side was accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "p.yaml: 'side' must be odd, got 6");
  }
}
