#pragma once
// The project's RGB-D sequence folders (docs/formats.md) read and written as FrameBuffers, for
// the C++17 callers of cropsight/bridge/ (bag export and import). Errors: cropsight::Error
// (cropsight/core/error.hpp, valid C++17) naming the file and the problem.
// Not thread-safe per object.
#include <memory>
#include <string>

#include "cropsight/bridge/frame_buffers.hpp"

namespace cropsight::bridge {

class SequenceSource {
 public:
  /// Opens and validates `dir` (io::SequenceReader). Throws Error(path, ...).
  explicit SequenceSource(const std::string& dir);
  ~SequenceSource();
  SequenceSource(const SequenceSource&) = delete;
  SequenceSource& operator=(const SequenceSource&) = delete;

  int size() const;
  bool has_color() const;
  const CameraModel& camera() const;
  /// Frame `index` without its label image. Throws Error naming the image file.
  FrameBuffers read(int index) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes a sequence folder through a temporary sibling renamed by finish() (io::SequenceWriter):
/// a sink destroyed without finish() leaves nothing under `dir`.
class SequenceSink {
 public:
  /// Throws Error(dir, ...) when `dir` exists and `overwrite` is false, or `camera` is invalid.
  SequenceSink(const std::string& dir, const CameraModel& camera, bool overwrite = false);
  ~SequenceSink();
  SequenceSink(const SequenceSink&) = delete;
  SequenceSink& operator=(const SequenceSink&) = delete;

  /// Frames in order 0, 1, 2, ...; their size must be the camera's. Throws Error("frame N", ...).
  void write(const FrameBuffers& frame);
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::bridge
