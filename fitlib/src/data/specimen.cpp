// Specimen constants of a waveform record (formats.md §2): the keys and their checks, and the
// force/displacement conversion (docs/data.md "Waveform").
#include "fitlib/data/specimen.hpp"

#include <cmath>
#include <map>

#include "fitlib/data/csv.hpp"
#include "specimen_keys.hpp"

namespace fitlib::data {
namespace {

using core::InputError;

enum class KeyKind { text, number, count, mode };
const std::map<std::string, KeyKind>& metadata_keys() {
  static const std::map<std::string, KeyKind> keys = {
      {"mode", KeyKind::mode},           {"area_mm2", KeyKind::number},
      {"thickness_mm", KeyKind::number}, {"length_mm", KeyKind::number},
      {"volume_mm3", KeyKind::number},   {"n_specimens", KeyKind::count},
      {"temperature_C", KeyKind::number}, {"material", KeyKind::text},
      {"specimen", KeyKind::text},       {"orientation", KeyKind::text}};
  return keys;
}

constexpr int kMaxSpecimens = 1000;  // specimens loaded in parallel (2 in a double sandwich)

void apply_mode(SpecimenInfo& info, const std::string& label, const specimen_keys::ErrorAt& error) {
  const auto mode = core::test_mode_from_label(label);
  if (!mode) throw error("unknown test mode '" + label + "' (expected " + kModeLabels + ")");
  info.mode = *mode;
  info.has_mode = true;
}

void apply_count(SpecimenInfo& info, double count, const specimen_keys::ErrorAt& error) {
  if (count < 1.0 || count > kMaxSpecimens || count != std::floor(count))
    throw error("'n_specimens' must be a whole number from 1 to " + std::to_string(kMaxSpecimens));
  info.n_specimens = static_cast<int>(count);
}

void apply_number(SpecimenInfo& info, const std::string& key, double number) {
  if (key == "area_mm2") info.area_mm2 = number;
  if (key == "thickness_mm") info.thickness_mm = number;
  if (key == "length_mm") info.length_mm = number;
  if (key == "volume_mm3") info.volume_mm3 = number;
  if (key == "temperature_C") info.temperature_C = number;
}

void apply_text(SpecimenInfo& info, const std::string& key, const std::string& text,
                const specimen_keys::ErrorAt& error) {
  if (key == "material") info.material = text;
  if (key == "specimen") info.specimen = text;
  if (key == "orientation") {
    if (!is_known_orientation(text))
      throw error("unknown orientation '" + text + "' (expected " + kOrientationLabels + ")");
    info.orientation = text;
  }
}

}  // namespace

namespace specimen_keys {

bool is_numeric(const std::string& key) {
  const auto kind = metadata_keys().find(key);
  return kind != metadata_keys().end() &&
         (kind->second == KeyKind::number || kind->second == KeyKind::count);
}

void apply(SpecimenInfo& info, const std::string& key, const nlohmann::json& value,
           const ErrorAt& error) {
  const auto it = metadata_keys().find(key);
  if (it == metadata_keys().end())
    throw error("unknown specimen key '" + key +
                "' (known: mode, area_mm2, thickness_mm, length_mm, volume_mm3, n_specimens, "
                "temperature_C, material, specimen, orientation)");
  const KeyKind kind = it->second;
  if (kind == KeyKind::number || kind == KeyKind::count) {
    if (!value.is_number() || !std::isfinite(value.get<double>()))
      throw error("'" + key + "' must be a finite number");
  } else if (!value.is_string()) {
    throw error("'" + key + "' must be a string");
  }
  switch (kind) {
    case KeyKind::mode: apply_mode(info, value.get<std::string>(), error); break;
    case KeyKind::count: apply_count(info, value.get<double>(), error); break;
    case KeyKind::number: apply_number(info, key, value.get<double>()); break;
    case KeyKind::text: apply_text(info, key, value.get<std::string>(), error); break;
  }
}

}  // namespace specimen_keys

void stress_strain_from_force(const SpecimenInfo& specimen, const std::vector<double>& force_N,
                              const std::vector<double>& displacement_mm,
                              std::vector<double>& stress_MPa, std::vector<double>& strain) {
  const auto require = [](double value, const char* key) {
    if (!(value > 0.0))
      throw InputError(std::string("specimen ") + key +
                           " must be given and positive for force/displacement input",
                       "", 0, 0, key);
    return value;
  };
  if (!specimen.has_mode) throw InputError("specimen mode is required", "", 0, 0, "mode");
  if (specimen.n_specimens < 1)
    throw InputError("n_specimens must be at least 1", "", 0, 0, "n_specimens");
  const double area_mm2 = require(specimen.area_mm2, "area_mm2");
  double force_to_stress = 0.0, displacement_to_strain = 0.0;
  switch (specimen.mode) {
    case core::TestMode::shear:  // τ = F/(n·A), γ = u/h (each sandwich layer sees u)
      force_to_stress = 1.0 / (specimen.n_specimens * area_mm2);
      displacement_to_strain = 1.0 / require(specimen.thickness_mm, "thickness_mm");
      break;
    case core::TestMode::uniaxial:  // σ = F/(n·A), ε = u/L
      force_to_stress = 1.0 / (specimen.n_specimens * area_mm2);
      displacement_to_strain = 1.0 / require(specimen.length_mm, "length_mm");
      break;
    case core::TestMode::bulk:  // p = F/A on the piston, ε_v = ΔV/V0 = A·u/V0
      force_to_stress = 1.0 / area_mm2;
      displacement_to_strain = area_mm2 / require(specimen.volume_mm3, "volume_mm3");
      break;
  }
  stress_MPa.resize(force_N.size());
  strain.resize(displacement_mm.size());
  for (std::size_t i = 0; i < force_N.size(); ++i) stress_MPa[i] = force_N[i] * force_to_stress;
  for (std::size_t i = 0; i < displacement_mm.size(); ++i)
    strain[i] = displacement_mm[i] * displacement_to_strain;
}

}  // namespace fitlib::data
