#include "testing/testing.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::testing {

namespace fs = std::filesystem;

TempDir::TempDir() {
  std::random_device rd;
  for (int attempt = 0; attempt < 100; ++attempt) {
    fs::path p =
        fs::temp_directory_path() / ("cropsight-test-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
    if (fs::create_directory(p)) {
      path_ = p;
      return;
    }
  }
  throw std::runtime_error("cannot create a temporary directory");
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

fs::path source_dir() { return CROPSIGHT_SOURCE_DIR; }

fs::path shared_data_dir() {
  if (const char* env = std::getenv("CROPSIGHT_DATA")) return env;
  return fs::weakly_canonical(fs::path(CROPSIGHT_SHARED_DATA_DIR));
}

fs::path cli_path() { return CROPSIGHT_CLI; }

CommandResult run_cli(const std::string& args) {
  TempDir tmp;
  const fs::path out = tmp / "out.txt", err = tmp / "err.txt";
  const std::string cmd =
      "'" + cli_path().string() + "' " + args + " >'" + out.string() + "' 2>'" + err.string() + "' </dev/null";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

std::string error_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const cropsight::Error& e) {
    return e.what();
  }
  return "";
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) throw std::runtime_error("cannot write fixture " + path.string());
}

}  // namespace cropsight::testing
