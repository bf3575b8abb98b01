#include "fuzz_common.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fitlib::fuzz {

void finding(const std::string& what) {
  std::fprintf(stderr, "fitlib fuzz finding: %s\n", what.c_str());
  std::abort();
}

std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  static const std::filesystem::path folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    auto dir = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
               ("fitlib-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
  }();
  const std::string path = (folder / ("input" + extension)).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace fitlib::fuzz
