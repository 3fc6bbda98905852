#pragma once
// The potato pipeline (pipeline::potato::Pipeline) behind a C++17 header, for the ROS node.
// One runner per camera; not thread-safe. Errors: cropsight::Error naming the file or input.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/bridge/frame_buffers.hpp"
#include "cropsight/pipeline/potato/frame_result.hpp"

namespace cropsight::bridge {

struct PotatoRunnerOptions {
  std::string preset = "potato";  ///< preset name (configs/) or YAML path
  std::vector<std::string> sets;  ///< "key=value" overrides (--set)
};

class PotatoRunner {
 public:
  /// Loads and validates the preset. Throws Error(file or "--set", ...).
  explicit PotatoRunner(const PotatoRunnerOptions& options);
  ~PotatoRunner();
  PotatoRunner(const PotatoRunner&) = delete;
  PotatoRunner& operator=(const PotatoRunner&) = delete;

  /// One frame: colour required, depth optional (empty vector). Throws Error("frame N", ...) on
  /// a size mismatch.
  pipeline::potato::FrameResult process(const FrameBuffers& frame);
  /// Starts a new approach (drops the target).
  void reset();
  std::vector<std::string> class_names() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::bridge
