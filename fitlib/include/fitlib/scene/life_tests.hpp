#pragma once
// Life tests (docs/fatigue.md §6 "Life tests"): drive scenes with the life each belt was seen to
// last and how it failed. Each scene runs to the stresses its own life reads (its [life] level),
// and the peaks of every monitored point of the observed mode become one observed case of
// fatigue::fit_life_law. A CSV, one row per test:
//   [case,] scene, failure_mode, observed_h | observed_cycles [, a.scene.key ...]
// `scene` relative to the CSV's folder; a column whose name holds a dot sets that scene key for
// the row (as a sweep's [set]: conditions.temperature_C, drive.torque_Nm, …; empty = unchanged).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "fitlib/fatigue/card.hpp"
#include "fitlib/fatigue/life_fit.hpp"
#include "fitlib/scene/output_paths.hpp"
#include "fitlib/scene/sweep.hpp"

namespace fitlib::scene {

struct LifeTest {
  std::string name;        // `case`, or "line N"
  std::string scene_path;  // resolved against the CSV's folder
  fatigue::Mode mode = fatigue::Mode::radial_crack;
  bool runout = false;           // failure_mode "none": the test stopped without failing (mode unused)
  double observed_h = 0.0;       // > 0 when the row gives hours (cycles from the scene's belt speed)
  double observed_cycles = 0.0;  // > 0 when it gives cycles
  std::vector<std::pair<std::string, SweepValue>> scene_keys;  // key path, value
  int line = 0;
};

// True when the CSV's header names a `scene` column (a life-test list rather than stored peaks).
bool names_scenes(const std::string& csv_text, const std::string& source);

// InputError naming source, line, column and key for anything malformed.
std::vector<LifeTest> parse_life_tests(const std::string& csv_text, const std::string& source);

// The files a life-test list's scenes read (each scene with its row's keys set, and the cards it
// names) are inputs too: UsageError (refuse_outputs_on_inputs) for an output among them, before any
// scene runs (`life-fit --out` over a tests' card had replaced it). Nothing for stored peaks.
void refuse_outputs_on_test_scenes(const std::string& csv_text, const std::string& source,
                                   const std::vector<NamedPath>& outputs);

// Called before each test runs: (test, 1-based index, count).
using LifeTestProgress = std::function<void(const LifeTest&, std::size_t, std::size_t)>;

// Each test's scene (keys set) run to its stresses; the observed cases with `card`'s crack sweep.
// A scene's failure is rethrown with the CSV's file and line in front (same error type).
std::vector<fatigue::ObservedLife> observe_life_tests(const std::vector<LifeTest>& tests, const std::string& source,
                                                     const fatigue::FatigueCard& card,
                                                     const LifeTestProgress& progress = {});

// The observed cases of a CSV's text: a life-test list (scenes run; relative to the folder of
// `source`, the file's name) or the observed-lives CSV of stored peaks
// (fatigue::parse_observed_lives), told apart by the header.
std::vector<fatigue::ObservedLife> observed_cases(const std::string& csv_text, const std::string& source,
                                                  const fatigue::FatigueCard& card,
                                                  const LifeTestProgress& progress = {});

// A fatigue card fitted to the observed cases of a CSV's text (observed_cases, then
// fatigue::fit_life_card) from the fatigue card at `start_path` ("" = fatigue::default_card()):
// the card named after `source`, its provenance naming the observed file with its sha256 and case
// count and the start card.
struct LifeTestsFit {
  std::vector<fatigue::ObservedLife> cases;
  fatigue::LifeCardFit fit;
};
LifeTestsFit fit_life_tests(const std::string& csv_text, const std::string& source, const std::string& start_path,
                            const fatigue::HeldConstants& held = {},
                            const LifeTestProgress& progress = {});

}  // namespace fitlib::scene
