#include "fitlib/core/file_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "fitlib/core/error.hpp"

namespace fitlib::core {

OutputLock::OutputLock(const std::string& output) : path_(output + ".lock") {
  // The holder removes the file when it is done: a lock taken on a file that was removed (or
  // replaced) meanwhile is no lock, so take it again on what the path now names.
  for (int attempt = 0; attempt < 100; ++attempt) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw InputError(std::string("cannot create the lock file (") + std::strerror(errno) + ")", path_);
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw InputError("another run is writing this output now (its lock " + path_ +
                           " is held); wait for it to finish, or give another --out",
                       output);
    }
    struct stat held {}, named {};
    if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev)
      return;
    ::close(fd_);
    fd_ = -1;
  }
  throw InputError("cannot take the lock file: it is replaced as it is taken", path_);
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace fitlib::core
