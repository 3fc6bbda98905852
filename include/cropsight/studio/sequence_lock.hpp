#pragma once
// One writer per sequence: a studio that may write labels holds an exclusive lock on the hidden
// file SEQ/.cropsight-studio.lock (flock), so a second studio on the same sequence is refused or
// opens it read-only, never as a second writer. The kernel drops the lock when the process ends
// in any way (Ctrl-C, kill -9, a crash), so a stale lock never blocks the next studio; a clean
// stop also removes the file. Sequence readers skip hidden names.
#include <filesystem>

namespace cropsight::studio {

class SequenceLock {
 public:
  /// Tries to lock `sequence`; held() says whether it got the lock. Throws Error(lock file, ...)
  /// when the lock file cannot be created (a read-only folder).
  explicit SequenceLock(const std::filesystem::path& sequence);
  ~SequenceLock();
  SequenceLock(const SequenceLock&) = delete;
  SequenceLock& operator=(const SequenceLock&) = delete;

  bool held() const { return fd_ >= 0; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace cropsight::studio
