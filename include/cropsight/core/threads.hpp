#pragma once
// The one thread-count rule of the library and the CLI.
#include <string>

#include "cropsight/core/error.hpp"

namespace cropsight {

/// Largest thread count accepted anywhere (libtorch, XGBoost, FPFH, feature rows): far beyond any
/// machine this runs on, while libtorch hangs and OpenMP / XGBoost crash when asked for, say,
/// 100000 threads.
inline constexpr int kMaxThreads = 256;

/// Throws Error(where, ...) unless 1 <= threads <= kMaxThreads.
inline void check_thread_count(int threads, const std::string& where) {
  if (threads < 1 || threads > kMaxThreads)
    throw Error(where, "must be in 1.." + std::to_string(kMaxThreads) + ", got " + std::to_string(threads));
}

}  // namespace cropsight
