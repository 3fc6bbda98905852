#include "ros_test_support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "cropsight/core/error.hpp"

namespace fs = std::filesystem;

namespace cropsight::ros_test {

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string cli() { return CROPSIGHT_CLI; }

fs::path scratch_dir(const std::string& name) {
  const fs::path d = fs::path(CROPSIGHT_ROS_TEST_DIR) / "scratch" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string fixture_master_uri() {
  std::ifstream in(fs::path(CROPSIGHT_ROS_TEST_DIR) / "master_uri");
  std::string uri;
  std::getline(in, uri);
  return uri;
}

NodeProcess::NodeProcess(const std::string& executable, const std::vector<std::string>& args,
                         const std::string& log_file) {
  std::vector<std::string> argv_s{executable};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  pid_ = fork();
  if (pid_ == 0) {
    const int fd = open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    std::vector<char*> argv;
    for (auto& s : argv_s) argv.push_back(s.data());
    argv.push_back(nullptr);
    execv(executable.c_str(), argv.data());
    _exit(127);
  }
}

NodeProcess::~NodeProcess() { stop(2.0); }

bool NodeProcess::alive() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
    pid_ = -1;
    return false;
  }
  return true;
}

int NodeProcess::stop(double timeout_s) {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGINT);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  while (std::chrono::steady_clock::now() < end) {
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid_, SIGKILL);
  waitpid(pid_, &status, 0);
  pid_ = -1;
  return -1;
}

}  // namespace cropsight::ros_test
