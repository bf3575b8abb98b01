// Waveform signal files with `# key = value` metadata and an optional JSON specimen sidecar
// (formats.md §2), read as `fitcli waveform --signals F [--specimen S]` reads them. The input is
// the signal file, optionally followed by a line `%%sidecar` and the sidecar's bytes. The
// analysis of what was read has its own harness (fuzz_waveform_analysis.cpp).
#include "waveform_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto input = fitlib::fuzz::write_waveform_input(data, size);
  return fitlib::fuzz::run_reader([&] { fitlib::fuzz::read_checked_waveform(input); });
}
