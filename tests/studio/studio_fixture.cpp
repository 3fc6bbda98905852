// The studio tests' simulated pass and running server (studio_fixture.hpp).
#include "studio_fixture.hpp"

#include <chrono>

namespace cropsight::studio_testing {

namespace fs = std::filesystem;

const fs::path& simulated_pass() {
  // One pass for the whole binary: simulating takes a second, each test copies it.
  static const testing::TempDir dir;
  static const fs::path seq = [] {
    const fs::path out = dir / "pass";
    const auto r =
        testing::run_cli("simulate broccoli --frames 4 --seed 7 --quiet --out " + testing::shell_quoted(out));
    if (r.exit_code != 0) throw std::runtime_error("simulate broccoli failed: " + r.err);
    return out;
  }();
  return seq;
}

fs::path unlabelled_copy(const fs::path& dir) {
  const fs::path seq = dir / "seq";
  fs::copy(simulated_pass(), seq, fs::copy_options::recursive);
  fs::remove_all(seq / "labels");
  fs::remove(seq / "groundtruth.json");
  return seq;
}

RunningStudio::RunningStudio(studio::StudioOptions options)
    : server_(std::make_unique<studio::StudioServer>(std::move(options))) {
  thread_ = std::thread([this] { server_->run(); });
}

RunningStudio::~RunningStudio() {
  server_->stop();
  thread_.join();
}

httplib::Client RunningStudio::client() const {
  httplib::Client c("127.0.0.1", server_->port());
  c.set_default_headers({{"X-Cropsight-Token", server_->token()}});
  return c;
}

httplib::Client RunningStudio::anonymous() const { return httplib::Client("127.0.0.1", server_->port()); }

nlohmann::json wait_for_job(httplib::Client& client, const std::string& path) {
  for (int k = 0; k < 600; ++k) {
    auto j = nlohmann::json::parse(client.Get(path)->body);
    if (j["state"] != "running") return j;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return nullptr;
}

}  // namespace cropsight::studio_testing
