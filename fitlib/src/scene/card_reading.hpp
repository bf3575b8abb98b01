#pragma once
// Internal to the scene module: the strain amplitudes the segment drove each role's card at, and the
// cards read at them (card_reading.cpp; docs/fatigue.md §8).
#include <array>
#include <map>
#include <string>
#include <vector>

#include "effects.hpp"
#include "fitlib/segment/cycle.hpp"

namespace fitlib::scene::detail {

// A role's largest strain oscillation over the last cycle at its monitored points:
// `strain_amplitude`, half the range of e11, e22 and 2 e12 (logarithmic, belt frame), the largest
// component at any point — the measure the cards' data windows are read against; `components`, the
// amplitude with signs, half the difference of (e11, e22, 2 e12) between the two instants of one
// point whose deviatoric strains lie furthest apart (`deviatoric_norm` its deviatoric norm): the
// oscillation an elastic equivalent is read at (model::PointOptions::strain_amplitude).
struct ReachedAmplitude {
  double strain_amplitude = 0.0, deviatoric_norm = 0.0;
  std::array<double, 3> components{{0.0, 0.0, 0.0}};
};
std::map<std::string, ReachedAmplitude> reached_amplitudes(const segment::CycleResult& run);
// The same measure per element, from its mean over its integration points (segment::CycleOutputs::
// record_elements), in mesh order; empty when the run did not record them.
std::vector<ReachedAmplitude> element_amplitudes(const segment::CycleResult& run);
// (e11, e22, 0, 0, 0, γ12) of a reached amplitude.
model::Vector6 voigt_amplitude(const ReachedAmplitude& amplitude);

// What the run read of each role's card: its conditions, the amplitude it was read at (`read_at`,
// the elastic iteration's; none: small amplitude or the complete level) and the one it reached.
std::vector<CardReading> card_readings(const Scene& scene, core::Fidelity fidelity, double frequency_Hz,
                                       const std::map<std::string, ReachedAmplitude>& reached,
                                       const std::map<std::string, ReachedAmplitude>& read_at);
// "cushion read at 13x its largest tested amplitude (0.58 against 0.045)", or empty within the tests.
std::string beyond_tests_clause(const CardReading& reading);
// [life] beyond_tests = "refuse": InputError (key life.beyond_tests) when a card was read beyond its tests.
void refuse_beyond_tests(const Scene& scene, const std::vector<CardReading>& readings);
// A mode whose role's card (bottom: radial crack, cushion: separation) was read beyond its tests says
// so and is printed with fatigue::kDigitsBeyondTests significant digits.
void mark_lives_beyond_tests(const std::vector<CardReading>& readings, fatigue::LifeReport& report);

}  // namespace fitlib::scene::detail
