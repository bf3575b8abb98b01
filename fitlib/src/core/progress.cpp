#include "fitlib/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace fitlib::core {

Progress::Progress(std::string label, std::size_t total, bool force)
    : label_(std::move(label)), total_(total), enabled_(force || isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  if (enabled_ && last_percent_ >= 0) std::fputc('\n', stderr);
}

void Progress::advance(std::size_t steps) {
  done_ += steps;
  if (!enabled_ || total_ == 0) return;
  const int percent = static_cast<int>(100 * (done_ > total_ ? total_ : done_) / total_);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  std::fprintf(stderr, "\r%s: %3d %% (%zu/%zu)", label_.c_str(), percent, done_, total_);
  std::fflush(stderr);
}

}  // namespace fitlib::core
