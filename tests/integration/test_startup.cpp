// fitcli's start-up (docs/fitting.md "Speed", docs/decisions.md "fitcli start-up: the Ceres stack's
// libraries linked statically"): which shared libraries the process loads, and that exceptions
// still unwind through the compiler's run-time when glog's libunwind is loaded beside it.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace {

// stderr of `fitcli --version` with the dynamic loader's variable `env` set (glibc's ld.so
// writes its traces there; LD_TRACE_LOADED_OBJECTS lists the objects on stdout, as ldd does).
std::string loader_output(const std::string& env) {
  static int runs = 0;
  const std::string base = temp_file("startup_" + std::to_string(++runs));
  const std::string cmd = env + " " + FITCLI_EXE + " --version >" + base + ".out 2>" + base + ".err";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
  return slurp(base + ".out") + slurp(base + ".err");
}

// Under AddressSanitizer libasan intercepts _Unwind_RaiseException, so libstdc++'s throw binds to
// it (which then calls the next definition); what stays checkable there is that libunwind is not it.
#ifdef __SANITIZE_ADDRESS__
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif

}  // namespace

// --version leaves CLI11's parse by an exception: libstdc++'s throw binds _Unwind_RaiseException
// to the first loaded library defining it; libunwind (glog's) defines it too, and was first when
// the static archives' dependencies were added ahead of libgcc_s.
TEST(Startup, ExceptionsUnwindThroughTheCompilersRunTime) {
  const std::string trace = loader_output("LD_DEBUG=bindings");
  std::size_t raise = 0, from_libunwind = 0;
  for (std::size_t at = trace.find("`_Unwind_RaiseException'"); at != std::string::npos;
       at = trace.find("`_Unwind_RaiseException'", at + 1)) {
    ++raise;
    const std::size_t line = trace.rfind('\n', at);
    const std::string binding = trace.substr(line == std::string::npos ? 0 : line, at - line);
    if (binding.find("libunwind") != std::string::npos) ++from_libunwind;
    const bool intercepted = kAddressSanitizer && binding.find("libasan") != std::string::npos;
    EXPECT_TRUE(intercepted || binding.find("libgcc_s") != std::string::npos) << binding;
  }
  EXPECT_GT(raise, 0u) << "no binding of _Unwind_RaiseException traced";
  EXPECT_EQ(from_libunwind, 0u);
}

#ifdef FITLIB_STATIC_DEPS
// SuiteSparse, glog, gflags and freexl come from their static archives (FITLIB_STATIC_DEPS):
// the process maps none of their shared libraries.
TEST(Startup, FitcliLoadsNoSuiteSparseGlogOrFreexlLibrary) {
  const std::string objects = loader_output("LD_TRACE_LOADED_OBJECTS=1");
  ASSERT_NE(objects.find("libc.so"), std::string::npos) << objects;
  for (const char* lib : {"libcholmod", "libumfpack", "libamd", "libcxsparse", "libspqr", "libsuitesparseconfig",
                          "libglog", "libgflags", "libfreexl"})
    EXPECT_EQ(objects.find(lib), std::string::npos) << lib << " loaded:\n" << objects;
}

// LAPACK/BLAS/ATLAS, the compiler's Fortran, quad-precision and OpenMP run-times, toml++ (compiled
// into fitcli) and libstdc++ come from archives too (docs/decisions.md "fitcli start-up: libstdc++,
// toml++ and LAPACK in the executable"): none of their shared libraries is mapped, so the process
// holds one C++ run-time, and an exception thrown inside toml++'s parser still reaches fitcli's
// handler (a scene with a broken table header: exit 3 and the parser's own message). Under the
// sanitizers libstdc++ stays shared (cmake/link-static-deps.sh).
TEST(Startup, FitcliLoadsNoCxxRuntimeTomlOrLapackLibrary) {
  const std::string objects = loader_output("LD_TRACE_LOADED_OBJECTS=1");
  ASSERT_NE(objects.find("libc.so"), std::string::npos) << objects;
  for (const char* lib : {"libtomlplusplus", "liblapack", "libblas", "libatlas", "libf77blas", "libgfortran",
                          "libquadmath", "libgomp"})
    EXPECT_EQ(objects.find(lib), std::string::npos) << lib << " loaded:\n" << objects;
#ifndef FITLIB_SANITIZED
  EXPECT_EQ(objects.find("libstdc++"), std::string::npos) << "libstdc++ loaded:\n" << objects;
#endif
  const std::string scene = temp_file("startup_broken_scene.toml");
  std::ofstream(scene) << "[belt\nx = 1\n";
  const CliResult r = run_fitcli("belt --scene " + scene + " --out-dir " + temp_file("startup_broken_scene_out"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("Error while parsing table header"), std::string::npos) << r.err;
}
#endif
