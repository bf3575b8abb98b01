#pragma once
// An exclusive lock on an output (docs/sweep.md "Resume"): two sweeps writing one --out appended
// to one FILE.partial and ended with a raw "filesystem error: cannot rename"; now the second is
// refused at once, naming the file.
#include <string>

namespace fitlib::core {

class OutputLock {
 public:
  // Takes flock(LOCK_EX | LOCK_NB) on `output` + ".lock" (created if missing); InputError naming
  // `output` when another process holds it. The kernel drops the lock when its holder dies, so a
  // killed run's leftover .lock file never blocks the next run.
  explicit OutputLock(const std::string& output);
  ~OutputLock();  // removes the .lock file and releases the lock
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace fitlib::core
