#pragma once
// Progress of a long run on stderr, shown only when stderr is a terminal (or when forced).
#include <cstddef>
#include <string>

namespace fitlib::core {

class Progress {
 public:
  Progress(std::string label, std::size_t total, bool force = false);
  ~Progress();
  void advance(std::size_t steps = 1);

 private:
  std::string label_;
  std::size_t total_, done_ = 0;
  int last_percent_ = -1;
  bool enabled_;
};

}  // namespace fitlib::core
