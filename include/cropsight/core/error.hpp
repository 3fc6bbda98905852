#pragma once
// The one error type of cropsight: it names the file (or input) and the problem, so that the
// CLI can print a single line "FILE: PROBLEM" and exit non-zero.
#include <stdexcept>
#include <string>

namespace cropsight {

class Error : public std::runtime_error {
 public:
  /// `where`: a file path, or a short name of the input ("--set", "config", "frame 12").
  /// `problem`: what is wrong, in words a user can act on, without a trailing period.
  Error(std::string where, std::string problem)
      : std::runtime_error(where.empty() ? problem : where + ": " + problem),
        where_(std::move(where)),
        problem_(std::move(problem)) {}

  const std::string& where() const noexcept { return where_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::string where_;
  std::string problem_;
};

}  // namespace cropsight
