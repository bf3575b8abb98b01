#pragma once
// Sweeps (docs/sweep.md): a grid of scene runs — scene files × axes of values set at dotted key
// paths of the scene TOML (any scalar: temperature, torque, a pulley's speed, a role's card) —
// and one row of result columns per case. Case i is a pure function of the sweep file and i, and
// each row's text depends on nothing else, so the table is the same for any number of threads or
// MPI ranks (sweep_run.hpp runs it).
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace fitlib::scene {

// Work cap (README "Work caps"): cases of one sweep file; 10⁶ beam-level life cases take about
// 0.2 core-hours (docs/sweep.md "Scaling", bench_sweep), segment-level ones far more.
constexpr double kMaxSweepCases = 1e6;

// Work cap in estimated cost: CPU time per case at each life fidelity level on the 2-core
// reference machine (beam: bench_sweep's 0.675 ms; elastic about 1 s, complete 2.5-3.5 s: README
// tour, bench_life), summed over the cases, at most a day of one core (docs/decisions.md
// "sweep: work cap in core-hours"). An elastic 10^6-case sweep (about 280 core-hours) is refused.
struct SweepCaseCosts {
  double beam, elastic, complete;
};
constexpr SweepCaseCosts kSweepCaseCostS{0.675e-3, 1.0, 3.5};
constexpr double kMaxSweepCoreHours = 24.0;


// The columns of a sweep file without [outputs]: the load cycle's headline figures and the life
// per mode at the planner's fidelity (docs/sweep.md "Columns").
inline const std::vector<std::string> kDefaultSweepColumns{
    "max_tension_N",  "max_sliding_arc_deg", "fidelity", "governing_mode", "life_h",
    "radial_crack_life_h", "separation_life_h"};

using SweepValue = std::variant<bool, std::int64_t, double, std::string>;

// One axis: the dotted key path it sets ("drive.torque_Nm", "drive.pulleys[0].speed_rpm",
// "belt.materials.bottom") and its values. `labels` are the values as the table prints them
// (card paths as written in the sweep file, numbers by core::format_number).
struct SweepAxis {
  std::string key;
  std::vector<SweepValue> values;
  std::vector<std::string> labels;
};

struct Sweep {
  std::string path;                     // the sweep file
  std::string name;
  std::vector<std::string> scenes;      // scene files (resolved against the sweep file's folder)
  std::vector<std::string> scene_labels;  // as written in the sweep file
  std::vector<std::string> scene_texts;   // their bytes, read once
  std::vector<SweepAxis> fixed;         // [set]: one value each, applied to every case
  std::vector<SweepAxis> axes;          // [[axis]], in file order (the last varies fastest)
  std::vector<std::string> columns;     // [outputs] columns
  std::vector<std::string> card_files;  // every card a case can read (its scene's or an axis's)
  std::string sha256;                   // of the sweep file and of every file it names
  std::size_t case_count = 0;
};

// Reads and validates a sweep file: unknown keys, wrong types, unknown columns, a value the scene
// rejects (each axis value is tried on the first scene), a grid above kMaxSweepCases — each an
// InputError naming the sweep file, line:column and key path.
Sweep load_sweep(const std::string& path);
Sweep parse_sweep(const std::string& toml_text, const std::string& source);

// The estimate: Σ over the cases of their level's cost (a case's level from the planner on its
// scene; an axis of cards, [life] or [segment] keys enumerated when at most 256 combinations,
// else its dearest value for every case), in core-hours.
double sweep_cost_core_hours(const Sweep& sweep);

// Case i of the grid: scene index and one value index per axis. Scenes vary slowest, then the
// axes in file order; the last axis varies fastest (mixed radix).
struct SweepCase {
  std::size_t index = 0, scene = 0;
  std::vector<std::size_t> value;
};
SweepCase sweep_case(const Sweep& sweep, std::size_t index);

// Result columns a sweep can ask for (docs/sweep.md "Columns").
const std::vector<std::string>& sweep_column_names();

// The table's header fields: case, scene, one per axis key, the asked columns, status, message.
std::vector<std::string> sweep_header(const Sweep& sweep);
// True for a header column that holds words (scene, status, message, fidelity, governing mode).
bool sweep_text_column(const std::string& name);

// The CSV row of case i (no newline). A case whose scene is rejected (a drive that slips) or
// whose solver fails gives status input_error or numerical_error, its message and empty result
// columns; every number is core::format_number's text, an unbounded life an empty field.
std::string sweep_row(const Sweep& sweep, std::size_t index);

// CSV fields: quoted when they hold a comma, quote or line break (RFC 4180), and split back.
std::string csv_field(const std::string& text);
std::vector<std::string> split_csv_row(const std::string& row);

}  // namespace fitlib::scene
