#pragma once
// The waveform harnesses' input: the signal file, optionally followed by a line `%%sidecar` and the
// specimen sidecar's bytes, written to two files of this process as fitcli would be given them.
#include "fitlib/data/waveform.hpp"
#include "fuzz_common.hpp"

namespace fitlib::fuzz {

struct WaveformInput {
  std::string signals_path, sidecar_path;  // sidecar_path empty: no sidecar
};

inline WaveformInput write_waveform_input(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::string marker = "\n%%sidecar\n";
  const auto split = bytes.find(marker);
  const std::string signals = bytes.substr(0, split);
  WaveformInput input;
  input.signals_path = write_input(reinterpret_cast<const std::uint8_t*>(signals.data()), signals.size(), ".csv");
  if (split != std::string::npos) {
    const std::string sidecar = bytes.substr(split + marker.size());
    input.sidecar_path = write_input(reinterpret_cast<const std::uint8_t*>(sidecar.data()), sidecar.size(), ".json");
  }
  return input;
}

// Reads the input; every sample it accepted must be finite.
inline data::WaveformRecord read_checked_waveform(const WaveformInput& input) {
  auto record = data::read_waveform(input.signals_path, input.sidecar_path);
  for (std::size_t i = 0; i < record.time_s.size(); ++i) {
    require_finite(record.time_s[i], "time");
    require_finite(record.stress_MPa[i], "stress");
    require_finite(record.strain[i], "strain");
  }
  return record;
}

}  // namespace fitlib::fuzz
