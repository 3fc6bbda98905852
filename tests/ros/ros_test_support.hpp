#pragma once
// Helpers of the ROS tests (C++17, like ros/): the CLI and scratch folders, and node processes.
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace cropsight::ros_test {

/// Runs a shell command; returns its exit status (-1 when it did not exit normally).
int run(const std::string& command);
/// The message of the cropsight::Error that `f` throws; "" when it throws none.
std::string error_of(const std::function<void()>& f);
/// The cropsight CLI built beside the tests.
std::string cli();
/// An empty folder under the build tree for one test.
std::filesystem::path scratch_dir(const std::string& name);
/// The master URI the CTest fixture (scripts/ros-master.sh) recorded; empty when none.
std::string fixture_master_uri();

/// A node executable started with ROS_MASTER_URI/ROS_HOSTNAME of this process and `args`
/// (remaps, _param:=value). stop() sends SIGINT (the node's shutdown path) and waits.
class NodeProcess {
 public:
  NodeProcess(const std::string& executable, const std::vector<std::string>& args, const std::string& log_file);
  ~NodeProcess();
  NodeProcess(const NodeProcess&) = delete;
  NodeProcess& operator=(const NodeProcess&) = delete;
  bool alive();
  /// SIGINT, then SIGKILL after `timeout_s`; returns the exit status (-1 when killed or not running).
  int stop(double timeout_s = 10.0);

 private:
  pid_t pid_ = -1;
};

}  // namespace cropsight::ros_test
