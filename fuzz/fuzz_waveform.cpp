// Waveform signal files with `# key = value` metadata and an optional JSON specimen sidecar
// (formats.md §2), read and analysed as `fitcli waveform --signals F [--specimen S]` does. The
// input is the signal file, optionally followed by a line `%%sidecar` and the sidecar's bytes.
#include "fitlib/data/waveform.hpp"
#include "fuzz_common.hpp"

using fitlib::fuzz::require_finite;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::string marker = "\n%%sidecar\n";
  const auto split = bytes.find(marker);
  const std::string signals = bytes.substr(0, split);
  const auto* p = reinterpret_cast<const std::uint8_t*>(signals.data());
  const std::string signals_path = fitlib::fuzz::write_input(p, signals.size(), ".csv");
  std::string sidecar_path;
  if (split != std::string::npos) {
    const std::string sidecar = bytes.substr(split + marker.size());
    sidecar_path = fitlib::fuzz::write_input(reinterpret_cast<const std::uint8_t*>(sidecar.data()),
                                             sidecar.size(), ".json");
  }
  return fitlib::fuzz::run_reader([&] {
    const auto record = fitlib::data::read_waveform(signals_path, sidecar_path);
    for (std::size_t i = 0; i < record.time_s.size(); ++i) {
      require_finite(record.time_s[i], "time");
      require_finite(record.stress_MPa[i], "stress");
      require_finite(record.strain[i], "strain");
    }
    const auto report = fitlib::data::analyse_waveform(record.time_s, record.stress_MPa, record.strain);
    const auto row = fitlib::data::waveform_row(report, record.specimen, signals_path);
    require_finite(row.condition.frequency_Hz, "analysed frequency");
    require_finite(row.condition.strain_amplitude, "analysed strain amplitude");
    require_finite(row.storage_MPa, "analysed storage modulus");
    require_finite(row.loss_MPa, "analysed loss modulus");
    if (row.has_mean_modulus) require_finite(row.mean_modulus_MPa, "analysed mean modulus");
  });
}
