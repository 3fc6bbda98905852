// The one-writer lock of a sequence (studio/sequence_lock.hpp).
#include "cropsight/studio/sequence_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "cropsight/core/error.hpp"

namespace cropsight::studio {

SequenceLock::SequenceLock(const std::filesystem::path& sequence) : path_(sequence / ".cropsight-studio.lock") {
  const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw Error(path_.string(), std::string("cannot create the studio's lock file: ") + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);  // another studio holds it; its file stays
    return;
  }
  fd_ = fd;
}

SequenceLock::~SequenceLock() {
  if (fd_ < 0) return;
  // Removed while still locked, so a studio starting meanwhile either locked the old file (and
  // then fails) or creates a fresh one after the removal.
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace cropsight::studio
