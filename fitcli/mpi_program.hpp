#pragma once
// fitcli is built without Open MPI (its start-up costs every process about 3 ms; docs/decisions.md
// "fitcli start-up: Open MPI only in fitcli-mpi"): a command that runs across MPI ranks (sweep,
// life's card draws), launched by mpirun, becomes FITCLI_MPI_PROGRAM from fitcli's own folder with
// the same arguments. The commands that call this are compiled once per program (CMakeLists.txt).
#ifdef FITCLI_MPI_PROGRAM
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fitlib/core/error.hpp"
#endif

namespace fitcli {

inline void become_mpi_program_under_mpirun(const char* command) {
#ifdef FITCLI_MPI_PROGRAM
  bool by_mpirun = false;
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) by_mpirun |= std::getenv(v) != nullptr;
  if (!by_mpirun) return;
  std::string self(4096, '\0');
  const ssize_t n = readlink("/proc/self/exe", self.data(), self.size() - 1);
  if (n <= 0)
    throw fitlib::core::UsageError(std::string(command) + " under mpirun: cannot find fitcli's own folder for " FITCLI_MPI_PROGRAM);
  self.resize(static_cast<std::size_t>(n));
  const std::string program = self.substr(0, self.rfind('/') + 1) + FITCLI_MPI_PROGRAM;
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  const std::string line((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> words;
  for (std::size_t at = 0; at < line.size();) {
    const std::size_t end = line.find('\0', at);
    words.push_back(line.substr(at, end - at));
    at = end == std::string::npos ? line.size() : end + 1;
  }
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  execv(program.c_str(), argv.data());
  throw fitlib::core::UsageError(std::string(command) + " under mpirun: cannot run " + program);
#else
  (void)command;
#endif
}

}  // namespace fitcli
