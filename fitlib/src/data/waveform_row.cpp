// The dynamic-test row (formats.md §1) of a waveform analysis.
#include "fitlib/core/error.hpp"
#include "fitlib/data/waveform.hpp"

namespace fitlib::data {

DynamicTestRow waveform_row(const WaveformReport& report, const SpecimenInfo& specimen,
                            const std::string& source_file) {
  if (report.loss_MPa < 0.0)
    throw core::InputError("negative loss modulus from the energy method (stress lags strain): "
                           "check the signs of the force and displacement signals",
                           source_file);
  DynamicTestRow row;
  auto& c = row.condition;
  c.mode = specimen.mode;
  c.orientation = specimen.orientation;
  c.frequency_Hz = report.frequency_Hz;
  c.temperature_C = specimen.temperature_C;
  c.strain_amplitude = report.strain_amplitude;
  c.mean_strain = report.mean_strain;
  row.storage_MPa = report.storage_MPa;
  row.loss_MPa = report.loss_MPa;
  row.has_mean_modulus = report.has_mean_modulus;
  row.mean_modulus_MPa = report.mean_modulus_MPa;
  row.material = specimen.material;
  row.specimen = specimen.specimen;
  row.source_file = source_file;
  return row;
}

}  // namespace fitlib::data
