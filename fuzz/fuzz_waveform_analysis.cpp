// `fitcli waveform` end to end: read (as fuzz_waveform.cpp) and analyse, the table row's moduli
// finite. The analysis costs far more per sample than reading, so scripts/fuzz.sh gives this
// harness a smaller -max_len (a few hundred samples) to keep its execution rate useful.
#include "waveform_input.hpp"

using fitlib::fuzz::require_finite;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto input = fitlib::fuzz::write_waveform_input(data, size);
  return fitlib::fuzz::run_reader([&] {
    const auto record = fitlib::fuzz::read_checked_waveform(input);
    const auto report = fitlib::data::analyse_waveform(record.time_s, record.stress_MPa, record.strain);
    const auto row = fitlib::data::waveform_row(report, record.specimen, input.signals_path);
    require_finite(row.condition.frequency_Hz, "analysed frequency");
    require_finite(row.condition.strain_amplitude, "analysed strain amplitude");
    require_finite(row.storage_MPa, "analysed storage modulus");
    require_finite(row.loss_MPa, "analysed loss modulus");
    if (row.has_mean_modulus) require_finite(row.mean_modulus_MPa, "analysed mean modulus");
  });
}
