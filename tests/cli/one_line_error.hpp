#pragma once
// The CLI's bad-input contract, as the tests check it: exit 2 and exactly one line on stderr that
// names `what` (the file, option or key at fault).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "testing/testing.hpp"

namespace cropsight::testing {

inline void expect_one_line_error(const CommandResult& r, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace cropsight::testing
