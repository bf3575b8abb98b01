#pragma once
// Writers of a scene run: the CSV tables, the JSON summary and life report, and the output
// folder. The only place where scene results become JSON.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/scene/results.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitlib::scene {

// The load history (s, t, pulley, zone, F, K, p, γ, sliding speed, friction used).
std::string load_history_csv(const SceneResult& r);
std::string accumulation_csv(const AccumulationMap& m);
std::string tension_test_csv(const belt::TensionTestResult& t);
// Effects (name, ran, status, reason, cost measure and, with wall_times, wall_s), one entry per
// registry effect. Wall times break byte-identical outputs, hence the switch.
nlohmann::json effects_json(const Plan& plan, bool wall_times = false);
// Human table of the effects: ran / not run, name, cost in ms, reason.
std::string effects_table(const Plan& plan);
// Human life report: fidelity and why, life per mode in cycles and hours with the design points,
// governing mode, the input files with sha256. Requires r.life.
std::string life_text(const Scene& scene, const SceneResult& r);
// The summary: plan, effects with wall times, stiffness, drive, per-pulley results, and the
// result of every other effect that ran.
nlohmann::json summary_json(const Scene& scene, const SceneResult& r, bool wall_times = false);
// life.json: scene, fidelity and why, input files with sha256, life per mode (fatigue's JSON),
// effects with their cost (wall times only with wall_times). Requires r.life.
nlohmann::json life_json(const Scene& scene, const SceneResult& r, bool wall_times);
// Writes load_history.csv, accumulation.csv, tension_test.csv, life.json (each if run) and
// summary.json into `dir` atomically; returns the files written.
std::vector<std::string> write_outputs(const Scene& scene, const SceneResult& r, const std::string& dir,
                                       bool wall_times = false);

}  // namespace fitlib::scene
