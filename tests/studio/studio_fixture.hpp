#pragma once
// A small simulated broccoli pass for the studio's tests (made once per test binary with the
// CLI), copied per test without its labels, and a studio server running on a thread.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "cropsight/studio/server.hpp"
#include "studio/http.hpp"
#include "testing/testing.hpp"

namespace cropsight::studio_testing {

/// The simulated pass (4 frames, with labels): made on first use, removed at exit.
const std::filesystem::path& simulated_pass();

/// A copy of simulated_pass() in `dir`/seq without labels/ and groundtruth.json; returns it.
std::filesystem::path unlabelled_copy(const std::filesystem::path& dir);

/// A studio on a thread; stopped and joined on destruction.
class RunningStudio {
 public:
  explicit RunningStudio(studio::StudioOptions options);
  ~RunningStudio();
  studio::StudioServer& server() { return *server_; }
  /// A client that sends the token as a header on every request.
  httplib::Client client() const;
  /// A client that sends no token.
  httplib::Client anonymous() const;

 private:
  std::unique_ptr<studio::StudioServer> server_;
  std::thread thread_;
};

/// Polls a background job's status (GET `path`, e.g. "/api/train") until it is not "running";
/// null after a minute.
nlohmann::json wait_for_job(httplib::Client& client, const std::string& path);

}  // namespace cropsight::studio_testing
