#include "fitlib/scene/scene.hpp"
#include "fitlib/scene/scene_toml.hpp"

#include "fitlib/core/file_kind.hpp"
#include "fitlib/core/toml_limits.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include <boost/algorithm/string/join.hpp>
#include <toml++/toml.h>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::scene {

int segment_threads(const Scene& scene) {
  const int threads = segment::solver_threads(scene.segment ? scene.segment->setup.solver : segment::SolverKnobs{});
  return scene.segment_thread_cap > 0 ? std::min(threads, scene.segment_thread_cap) : threads;
}

segment::CogSection cog_section(const Scene& scene) {
  segment::CogSection sec;
  auto geo = [&](const char* key, double fallback) {
    const auto it = scene.extra_geometry_mm.find(key);
    return it == scene.extra_geometry_mm.end() ? fallback : it->second;
  };
  sec.height_mm = scene.belt.height_mm;
  sec.cushion_mm = geo("cushion_mm", sec.cushion_mm);
  sec.cog_pitch_mm = geo("cog_pitch_mm", sec.cog_pitch_mm);
  sec.cog_depth_mm = geo("cog_depth_mm", sec.cog_depth_mm);
  sec.flank_angle_deg = geo("cog_flank_angle_deg", sec.flank_angle_deg);
  sec.land_half_width_mm = geo("cog_land_half_width_mm", sec.land_half_width_mm);
  sec.root_fillet_mm = geo("cog_root_fillet_mm", sec.root_fillet_mm);
  sec.tip_radius_mm = geo("cog_tip_radius_mm", sec.tip_radius_mm);
  return sec;
}

namespace {
using core::InputError;
using core::kPi;

// Reads one TOML table: every key must be consumed; typed getters name the key path on error.
constexpr const char* kUnknownKey =
    "unknown key (check the spelling and the unit suffix, e.g. _mm, _N, _deg; docs/belt.md \"Scene\")";

class Reader {
 public:
  Reader(const toml::table& t, std::string prefix, const std::string& file)
      : t_(t), prefix_(std::move(prefix)), file_(file) {}

  [[noreturn]] void fail(const std::string& key, const std::string& msg,
                         const toml::source_region& where) const {
    throw InputError(msg, file_, static_cast<int>(where.begin.line),
                     static_cast<int>(where.begin.column), path(key));
  }
  [[noreturn]] void fail(const std::string& key, const std::string& msg) const {
    const toml::node* n = t_.get(key);
    fail(key, msg, n ? n->source() : t_.source());
  }
  std::string path(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }

  bool has(const std::string& key) const { return t_.contains(key); }
  const toml::node* node(const std::string& key) {
    seen_.insert(key);
    return t_.get(key);
  }
  std::optional<double> number(const std::string& key, double lo = -INFINITY, double hi = INFINITY,
                               bool lo_open = false) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    std::optional<double> v;
    if (auto f = n->as_floating_point()) v = f->get();
    if (auto i = n->as_integer()) v = static_cast<double>(i->get());
    if (!v) fail(key, "expects a number in the unit its name ends with");
    if (!std::isfinite(*v) || *v < lo || *v > hi || (lo_open && *v == lo)) {
      std::ostringstream m;
      m << "value " << *v << " out of range " << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
      fail(key, m.str());
    }
    return v;
  }
  double number_or(const std::string& key, double fallback, double lo = -INFINITY,
                   double hi = INFINITY, bool lo_open = false) {
    return number(key, lo, hi, lo_open).value_or(fallback);
  }
  // A count (cycles, steps, nodes): a whole number in [lo, hi]; 2.5 cycles ran as 2.
  double count_or(const std::string& key, double fallback, double lo, double hi) {
    const auto v = number(key, lo, hi, false);
    if (v && *v != std::floor(*v)) fail(key, "must be a whole number, got " + core::format_number(*v));
    return v.value_or(fallback);
  }
  std::optional<std::string> string(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (auto s = n->as_string()) return s->get();
    fail(key, "expects a string");
  }
  std::optional<bool> boolean(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (auto b = n->as_boolean()) return b->get();
    fail(key, "expects true or false");
  }
  const toml::table* table(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return nullptr;
    if (auto t = n->as_table()) return t;
    fail(key, "expects a table");
  }
  // Unknown keys are errors, checked before any value so that a misspelt key is reported as such
  // (not as the missing key it was meant to be).
  Reader& allow(const std::vector<std::string>& keys) {
    for (auto&& [k, v] : t_) {
      const std::string key(k.str());
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
      fail(key, std::string(kUnknownKey) + "; this table takes " + boost::algorithm::join(keys, ", "), k.source());
    }
    return *this;
  }
  void finish() const {
    for (auto&& [k, v] : t_) {
      const std::string key(k.str());
      if (!seen_.count(key)) fail(key, kUnknownKey, v.source());
    }
  }
  const toml::table& raw() const { return t_; }

 private:
  const toml::table& t_;
  std::string prefix_;
  const std::string& file_;
  std::set<std::string> seen_;
};

belt::PulleyRole parse_role(Reader& r, const std::string& key) {
  const auto s = r.string(key);
  if (!s) r.fail(key, "missing: role = \"driver\", \"driven\" or \"idler\"");
  if (*s == "driver") return belt::PulleyRole::driver;
  if (*s == "driven") return belt::PulleyRole::driven;
  if (*s == "idler") return belt::PulleyRole::idler;
  r.fail(key, "role must be \"driver\", \"driven\" or \"idler\", not \"" + *s + "\"");
}

void apply_section(Scene& s, Reader& r) {
  s.section = r.string("section").value_or("cogged-0.500");
  if (s.section != "cogged-0.500")
    r.fail("section", "unknown section '" + s.section + "' (known: cogged-0.500)");
  // Defaults of the 0.500 in cogged belt (Report I §6.1, Eqs 6.2–6.3).
  s.belt = belt::BeltSection{};
  s.belt.height_mm = r.number_or("height_mm", 6.5862, 0.0, 1e3, true);
  s.belt.width_mm = r.number_or("width_mm", 11.1542, 0.0, 1e3, true);
  s.belt.area_mm2 = r.number_or("area_mm2", s.belt.height_mm * s.belt.width_mm, 0.0, 1e6, true);
  s.belt.density_kg_m3 = r.number_or("density_kg_m3", 1200.0, 0.0, 1e5);
  s.belt.wedge_half_angle_rad = r.number_or("wedge_half_angle_deg", 19.0, 0.0, 90.0, true) * kPi / 180.0;
  if (s.belt.wedge_half_angle_rad >= kPi / 2) r.fail("wedge_half_angle_deg", "must be below 90 deg");
  s.cord_area_mm2 = r.number_or("cord_area_mm2", 5.0, 0.0, 1e4, true);
  s.bending_inertia_mm4 = r.number_or("bending_inertia_mm4", 834.0, 0.0, 1e9, true);
  for (const char* k : {"cog_pitch_mm", "cog_depth_mm", "cushion_mm", "length_mm", "cog_flank_angle_deg",
                        "cog_land_half_width_mm", "cog_root_fillet_mm", "cog_tip_radius_mm"}) {
    const bool corner_round = std::string(k) == "cog_root_fillet_mm" || std::string(k) == "cog_tip_radius_mm";
    const auto v = r.number(k, 0.0, 1e6, !corner_round);
    // A sharp corner's stress is singular: it grows with mesh refinement, and the life's design
    // points (gap bottom, mid-cushion; docs/fatigue.md) would not see it.
    if (v && *v == 0.0)
      r.fail(k, "a sharp corner (0 mm) is a stress singularity that the segment's design points (gap bottom, "
                "mid-cushion) do not see and whose stress grows with mesh refinement; give the corner's round, "
                "e.g. the 0.500 in section's 0.75 mm fillet or 0.5 mm tip (docs/segment.md §Mesh)");
    if (v) s.extra_geometry_mm[k] = *v;
  }
}
// [segment] load case: strain, curvature (or radius), pressure.
void parse_segment_load(Reader& r, SegmentSpec& g) {
  g.load.strain = r.number_or("strain", 0.0, -0.5, 1.0);
  g.load.curvature_1_mm = r.number_or("curvature_1_mm", 0.0, -10.0, 10.0);
  if (auto R = r.number("radius_mm", 0.0, 1e9, true)) {
    if (r.has("curvature_1_mm")) r.fail("radius_mm", "give radius_mm or curvature_1_mm, not both");
    g.load.curvature_1_mm = 1.0 / *R;
  }
  g.load.pressure_MPa = r.number_or("pressure_MPa", 0.0, 0.0, 1e3);
}

// [segment] law, end condition, integration, load steps and mesh knobs.
void parse_segment_solver(Reader& r, SegmentSpec& g) {
  const std::string law = r.string("law").value_or("hencky");
  if (law != "neo-hookean" && law != "stvk" && law != "hencky")
    r.fail("law", "law must be \"hencky\", \"neo-hookean\" or \"stvk\"");
  g.setup.law = segment::elastic_law_from_string(law);
  const std::string ends = r.string("ends").value_or("radial");
  if (ends != "radial" && ends != "free") r.fail("ends", "ends must be \"radial\" or \"free\"");
  g.setup.ends = ends == "radial" ? segment::EndCondition::radial : segment::EndCondition::free;
  try {  // the segment module holds the names; the scene adds the file and key
    g.setup.solver.physics.integration = segment::integration_from_string(r.string("integration").value_or("reduced"));
  } catch (const core::UsageError& e) {
    r.fail("integration", e.what());
  }
  g.setup.solver.stepping.steps = static_cast<int>(r.count_or("steps", 4, 1, kMaxSegmentSteps));
  // The element loop's threads (default min(2, hardware)); the results do not depend on it.
  if (auto t = r.number("threads", 1, kMaxSegmentThreads)) {
    if (*t != std::floor(*t)) r.fail("threads", "threads must be a whole number");
    g.setup.solver.threads = static_cast<int>(*t);
  }
}

const std::vector<std::string> kSegmentMeshKeys = {"fine_size_mm", "coarse_size_mm", "central_pitches", "end_pitches",
                                                   "cushion_rows", "gap_size_mm", "column_growth", "row_growth"};

// [segment] mesh knobs over `mk`'s values (the static case's defaults, or the life's mesh).
void parse_segment_mesh(Reader& r, segment::MeshKnobs& mk) {
  mk.fine_size_mm = r.number_or("fine_size_mm", mk.fine_size_mm, 0.05, 100.0);
  mk.coarse_size_mm = r.number_or("coarse_size_mm", mk.coarse_size_mm, 0.05, 100.0);
  mk.central_pitches = r.number_or("central_pitches", mk.central_pitches, 0.0, 20.0, true);
  mk.end_pitches = r.number_or("end_pitches", mk.end_pitches, 0.0, 20.0);
  mk.cushion_rows = static_cast<int>(r.count_or("cushion_rows", mk.cushion_rows, 1, 100));
  mk.gap_size_mm = r.number_or("gap_size_mm", mk.gap_size_mm, 0.0, 100.0);  // 0: no grading
  mk.column_growth = r.number_or("column_growth", mk.column_growth, 0.05, 10.0);
  mk.row_growth = r.number_or("row_growth", mk.row_growth, 1.0, 3.0);
}

// [segment.materials.bottom|cushion]: E_MPa and nu per role, for a role without a [belt.materials]
// card (a card is what the segment runs: both given would leave one unused without a word).
void parse_segment_materials(const toml::table& mt, const Scene& scene, SegmentSpec& g, const std::string& source) {
  Reader mr(mt, "segment.materials", source);
  mr.allow({"bottom", "cushion"});
  for (int role = 0; role < 2; ++role) {
    const char* name = role == 0 ? "bottom" : "cushion";
    if (mr.has(name) && scene.materials.count(name))
      mr.fail(name, std::string("the scene's [belt.materials] ") + name + " card is the segment's " + name +
                        " material: give one of the two");
    if (const toml::table* et = mr.table(name)) {
      Reader er(*et, std::string("segment.materials.") + name, source);
      er.allow({"E_MPa", "nu"});
      g.setup.materials[role].E_MPa = er.number_or("E_MPa", g.setup.materials[role].E_MPa, 0.0, 1e7, true);
      g.setup.materials[role].nu = er.number_or("nu", g.setup.materials[role].nu, -0.99, 0.49999);
      er.finish();
    }
  }
  mr.finish();
}

// A user point must lie in the mesh its stresses are read from: located here, before the FE runs,
// so the refusal names the scene file, line and key (segment::locate knows neither).
void require_point_in_mesh(const Reader& r, const segment::Mesh& mesh, const segment::NamedPoint& p, std::size_t i,
                           const toml::source_region& where) {
  try {
    segment::locate(mesh, Eigen::Vector2d(p.x_mm, p.y_mm));
  } catch (const InputError&) {
    Eigen::Vector2d lo = mesh.X.front(), hi = mesh.X.front();
    for (const Eigen::Vector2d& x : mesh.X) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    lo.array() += 0.0, hi.array() += 0.0;  // -0 (the cord line) printed as 0
    r.fail("points[" + std::to_string(i) + "]",
           "point '" + p.name + "' (" + core::format_number(p.x_mm) + ", " + core::format_number(p.y_mm) +
               ") mm is outside the segment mesh (x from " + core::format_number(lo.x()) + " to " +
               core::format_number(hi.x()) + " mm, y from " + core::format_number(lo.y()) + " to " +
               core::format_number(hi.y()) + " mm, y = 0 the cord line; the cog profile bounds it below)",
           where);
  }
}

// [segment] points = [{name, x_mm, y_mm}, ...]: the user's named points.
void parse_segment_points(Reader& r, const toml::node& pts, SegmentSpec& g, const segment::Mesh& mesh,
                          const std::string& source) {
  const toml::array* a = pts.as_array();
  if (!a) r.fail("points", "expects an array of {name, x_mm, y_mm}");
  std::size_t i = 0;
  for (const toml::node& pn : *a) {
    if (!pn.as_table()) r.fail("points", "points[" + std::to_string(i) + "] must be a table", pn.source());
    Reader pr(*pn.as_table(), "segment.points[" + std::to_string(i) + "]", source);
    pr.allow({"name", "x_mm", "y_mm"});
    segment::NamedPoint p;
    p.name = pr.string("name").value_or("point" + std::to_string(i + 1));
    const auto x = pr.number("x_mm"), y = pr.number("y_mm");
    if (!x || !y) pr.fail("x_mm", "a point needs x_mm and y_mm", pn.source());
    p.x_mm = *x, p.y_mm = *y;
    pr.finish();
    require_point_in_mesh(r, mesh, p, i, pn.source());
    g.setup.points.push_back(p);
    ++i;
  }
}

// [segment]: load case, law, elastic constants per role, mesh and solver knobs, user points.
SegmentSpec parse_segment(const Scene& scene, const toml::table& t, const std::string& source) {
  Reader r(t, "segment", source);
  std::vector<std::string> keys = {"strain", "curvature_1_mm", "radius_mm", "pressure_MPa", "law", "ends",
                                   "steps", "integration", "points", "threads", "materials", "frequency_Hz",
                                   "scan"};
  keys.insert(keys.end(), kSegmentMeshKeys.begin(), kSegmentMeshKeys.end());
  r.allow(keys);
  SegmentSpec g;
  auto& sec = g.setup.section;
  sec = cog_section(scene);
  try {
    sec.validate();
  } catch (const InputError& e) {
    throw InputError(e.detail().empty() ? e.what() : e.detail(), source, 0, 0, e.key());
  }
  parse_segment_load(r, g);
  // Bent with the bottom inside, the section reaches the centre of curvature at K·H = 1.
  if (g.load.curvature_1_mm * sec.height_mm >= 1.0)
    r.fail(r.has("radius_mm") ? "radius_mm" : "curvature_1_mm",
           "a bend to radius " + core::format_number(1.0 / g.load.curvature_1_mm, 6) +
               " mm puts the section's bottom (height " + core::format_number(sec.height_mm) +
               " mm below the cord line) at or beyond the centre of curvature: the radius must exceed the height");
  parse_segment_solver(r, g);
  parse_segment_mesh(r, g.setup.mesh);
  parse_segment_mesh(r, g.life_mesh);  // `fitcli life`: the keys given change the life's mesh, the rest stay
  g.life_mesh_changed = std::any_of(kSegmentMeshKeys.begin(), kSegmentMeshKeys.end(), [&](const std::string& k) { return r.has(k); });
  if (const toml::table* mt = r.table("materials")) parse_segment_materials(*mt, scene, g, source);
  g.frequency_Hz = r.number("frequency_Hz", 0.0, 1e9, true);
  // The mesh these knobs give (bounded by the ranges above, so cheap to build): the points must lie
  // in it, and it sets the work cap.
  const segment::Mesh mesh = segment::build_mesh(sec, g.setup.mesh);
  if (const toml::node* pts = r.node("points")) parse_segment_points(r, *pts, g, mesh, source);
  g.scan_design_regions = r.boolean("scan").value_or(false);
  for (const char* k : {"strain", "curvature_1_mm", "radius_mm", "pressure_MPa", "law", "ends", "steps"})
    if (r.has(k)) g.static_case_keys.emplace_back(k);
  r.finish();
  const double elements = mesh.element_count();
  if (elements * g.setup.solver.stepping.steps > kMaxSegmentWork)
    r.fail(r.has("steps") ? "steps" : "fine_size_mm",
           std::to_string(static_cast<long>(elements)) + " elements x " + std::to_string(g.setup.solver.stepping.steps) +
               " steps exceeds the work cap 2e4 (docs/reliability.md, work caps)");
  return g;
}

}  // namespace

const std::vector<std::string>& effect_names() {
  static const std::vector<std::string> names{"bending_zones", "inertia", "full_ode",
                                              "driver_exit_ramp", "viscoelastic_tension", "heat_buildup"};
  return names;
}
const std::vector<std::string>& output_names() {
  static const std::vector<std::string> names{"load_history", "strain_accumulation", "cvt_thrust",
                                              "tension_test", "life"};
  return names;
}

namespace {

void parse_pulleys(Scene& s, Reader& drive, const std::string& source) {
  const toml::node* pulleys_n = drive.node("pulleys");
  if (!pulleys_n || !pulleys_n->as_array())
    drive.fail("pulleys", "expects an array of pulley tables {name, pitch_diameter_mm, role, ...}");
  std::size_t index = 0;
  for (const toml::node& pn : *pulleys_n->as_array()) {
    const std::string key = "pulleys[" + std::to_string(index) + "]";
    if (!pn.as_table()) drive.fail("pulleys", key + " must be a table", pn.source());
    Reader pr(*pn.as_table(), "drive." + key, source);
    pr.allow({"name", "pitch_diameter_mm", "role", "speed_rpm", "torque_Nm", "center_mm"});
    PulleySpec p;
    p.name = pr.string("name").value_or("pulley" + std::to_string(index + 1));
    const auto d = pr.number("pitch_diameter_mm", 0.0, 1e5, true);
    if (!d) pr.fail("pitch_diameter_mm", "missing (pitch diameter in mm)", pn.source());
    p.pitch_diameter_mm = *d;
    p.role = parse_role(pr, "role");
    p.speed_rpm = pr.number("speed_rpm", 0.0, 1e6);
    p.torque_Nm = pr.number_or("torque_Nm", 0.0, 0.0, 1e7);
    if (const toml::node* c = pr.node("center_mm")) {
      const toml::array* a = c->as_array();
      if (!a || a->size() != 2 || !(*a)[0].is_number() || !(*a)[1].is_number())
        pr.fail("center_mm", "expects [x, y] in mm");
      const double x = (*a)[0].value<double>().value(), y = (*a)[1].value<double>().value();
      if (!(std::abs(x) <= kMaxCoordinate_mm && std::abs(y) <= kMaxCoordinate_mm))
        pr.fail("center_mm", "expects finite coordinates within +-1e6 mm");
      p.center_mm = std::make_pair(x, y);
    }
    pr.finish();
    s.pulleys.push_back(p);
    ++index;
  }
  if (s.pulleys.size() < 2) drive.fail("pulleys", "a drive needs at least two pulleys");
}

void parse_drive(Scene& s, Reader& top, const toml::table& root, const std::string& source) {
  const toml::table* drive_t = top.table("drive");
  if (!drive_t && root.get("segment")) return;  // a static section case needs no drive (make_drive refuses later)
  if (!drive_t) top.fail("drive", "missing [drive] table", root.source());
  Reader drive(*drive_t, "drive", source);
  drive.allow({"pulleys", "center_distance_mm", "torque_Nm", "power_kW", "slack_tension_N",
               "tight_tension_N", "initial_tension_N"});
  parse_pulleys(s, drive, source);
  s.center_distance_mm = drive.number("center_distance_mm", 0.0, 1e6, true);
  const bool all_centres = std::all_of(s.pulleys.begin(), s.pulleys.end(),
                                       [](const PulleySpec& p) { return p.center_mm.has_value(); });
  if (s.pulleys.size() == 2 && !s.center_distance_mm && !all_centres)
    drive.fail("center_distance_mm", "missing (or give every pulley center_mm = [x, y])", drive_t->source());
  if (s.pulleys.size() > 2 && !all_centres)
    drive.fail("pulleys", "drives with more than two pulleys need center_mm = [x, y] on every pulley");
  s.torque_Nm = drive.number("torque_Nm", 0.0, 1e7);
  s.power_kW = drive.number("power_kW", 0.0, 1e6);
  if (s.torque_Nm && s.power_kW) drive.fail("power_kW", "give torque_Nm or power_kW, not both");
  int rules = 0;
  for (auto [key, rule] : {std::pair{"slack_tension_N", belt::TensionRule::slack},
                           std::pair{"tight_tension_N", belt::TensionRule::tight},
                           std::pair{"initial_tension_N", belt::TensionRule::initial}}) {
    if (auto v = drive.number(key, 0.0, 1e7)) {
      if (++rules > 1) drive.fail(key, "give one tensioning rule: slack_, tight_ or initial_tension_N");
      s.tension_rule = rule;
      s.tension_N = *v;
    }
  }
  if (rules == 0)
    drive.fail("slack_tension_N", "missing tensioning rule (slack_tension_N, tight_tension_N or initial_tension_N)",
               drive_t->source());
  drive.finish();
}

// A path relative to the scene's folder.
std::string scene_relative(const std::filesystem::path& base, const std::string& p) {
  std::filesystem::path f(p);
  return (f.is_absolute() ? f : base / f).lexically_normal().string();
}

// A card file the scene names, resolved against the scene's folder; a missing file fails at its key
// with the path that was tried (the card reader would name only the file, far from the scene).
std::optional<std::string> card_file(Reader& r, const char* key, const std::filesystem::path& base) {
  const auto p = r.string(key);
  if (!p) return std::nullopt;
  const std::string path = scene_relative(base, *p);
  if (!std::filesystem::is_regular_file(path))
    r.fail(key, "no card file " + std::filesystem::absolute(path).lexically_normal().string() +
                    (std::filesystem::path(*p).is_absolute()
                         ? std::string()
                         : " (a path is read from the scene's folder; a scene on stdin: the current folder)"));
  return path;
}

void parse_belt(Scene& s, Reader& top, const std::filesystem::path& base, const std::string& source) {
  const toml::table* belt_t = top.table("belt");
  toml::table empty;
  Reader br(belt_t ? *belt_t : empty, "belt", source);
  br.allow({"section", "height_mm", "width_mm", "area_mm2", "density_kg_m3", "wedge_half_angle_deg",
            "cord_area_mm2", "bending_inertia_mm4", "cog_pitch_mm", "cog_depth_mm", "cushion_mm",
            "length_mm", "materials", "stiffness", "cog_flank_angle_deg", "cog_land_half_width_mm",
            "cog_root_fillet_mm", "cog_tip_radius_mm"});
  apply_section(s, br);
  if (const toml::table* mt = br.table("materials")) {
    Reader mr(*mt, "belt.materials", source);
    mr.allow({"bottom", "cushion", "cord", "poisson_ratio"});
    for (const char* role : kCardRoles)
      if (auto p = card_file(mr, role, base)) s.materials[role] = *p;
    s.material_poisson_ratio = mr.number_or("poisson_ratio", s.material_poisson_ratio, 0.0, 0.5);
    if (!(s.material_poisson_ratio < 0.5))  // K = 2G0(1 + ν)/(3(1 − 2ν)) is then infinite
      mr.fail("poisson_ratio", "must be below 0.5 (a card without a bulk modulus gets K from it; an incompressible "
                               "card needs its own bulk modulus: fit with --bulk-modulus)");
    mr.finish();
  }
  if (const toml::table* st = br.table("stiffness")) {
    Reader sr(*st, "belt.stiffness", source);
    sr.allow({"c_N", "k1_MPa", "EI_Nmm2"});
    s.c_N = sr.number("c_N", 0.0, 1e12, true);
    s.k1_MPa = sr.number("k1_MPa", 0.0, 1e9, true);
    s.EI_Nmm2 = sr.number("EI_Nmm2", 0.0, 1e12);
    sr.finish();
  }
  br.finish();
}

AccumulationSpec parse_accumulation(const toml::table& t, const std::string& source) {
  Reader ar(t, "accumulation", source);
  ar.allow({"shear_stress_MPa", "cycles", "cycle_points", "omega_min_rad_s", "omega_max_rad_s",
            "omega_points", "kappa", "spectrum", "strain_limit"});
  AccumulationSpec a;
  a.shear_stress_MPa = ar.number_or("shear_stress_MPa", a.shear_stress_MPa, 0.0, 1e6, true);
  a.cycles = static_cast<long>(ar.count_or("cycles", 10000, 1, 1e12));
  a.cycle_points = static_cast<int>(ar.count_or("cycle_points", 50, 1, kMaxAccumulationPoints));
  a.omega_min_rad_s = ar.number_or("omega_min_rad_s", a.omega_min_rad_s, 0.0, 1e9, true);
  a.omega_max_rad_s = ar.number_or("omega_max_rad_s", a.omega_max_rad_s, 0.0, 1e9, true);
  if (a.omega_max_rad_s < a.omega_min_rad_s) ar.fail("omega_max_rad_s", "must be >= omega_min_rad_s");
  a.omega_points = static_cast<int>(ar.count_or("omega_points", 100, 1, kMaxAccumulationPoints));
  if (static_cast<double>(a.cycle_points) * a.omega_points > kMaxAccumulationWork)
    ar.fail("omega_points", "cycle_points x omega_points exceeds the work cap " + std::to_string(kMaxAccumulationWork) +
                                " (README, work caps)");
  a.kappa = ar.number("kappa", 0.0, 1e6);
  a.spectrum = ar.string("spectrum").value_or(a.spectrum);
  a.strain_limit = ar.number("strain_limit", 0.0, 1e6, true);
  ar.finish();
  return a;
}

CvtSpec parse_cvt(const toml::table& t, const std::string& source) {
  Reader vr(t, "cvt", source);
  vr.allow({"tight_tension_N", "slack_tension_N", "groove_half_angle_deg", "driver_wrap_deg",
            "driven_wrap_deg"});
  CvtSpec c;
  c.tight_tension_N = vr.number_or("tight_tension_N", 0.0, 0.0, 1e7);
  c.slack_tension_N = vr.number_or("slack_tension_N", 0.0, 0.0, 1e7);
  c.groove_half_angle_deg = vr.number_or("groove_half_angle_deg", c.groove_half_angle_deg, 0.0, 90.0, true);
  c.driver_wrap_rad = vr.number_or("driver_wrap_deg", 0.0, 0.0, 360.0) * kPi / 180.0;
  c.driven_wrap_rad = vr.number_or("driven_wrap_deg", 0.0, 0.0, 360.0) * kPi / 180.0;
  vr.finish();
  return c;
}

TensionTestSpec parse_tension_test(const toml::table& t, const std::string& source) {
  Reader tr(t, "tension_test", source);
  tr.allow({"rate_mm_min", "load_time_s", "S_N", "tau_T_s", "tau_eps_s", "nodes", "steps"});
  TensionTestSpec x;
  x.rate_mm_min = tr.number_or("rate_mm_min", x.rate_mm_min, 0.0, 1e6, true);
  x.load_time_s = tr.number_or("load_time_s", x.load_time_s, 0.0, 1e7, true);
  x.S_N = tr.number("S_N", 0.0, 1e12, true);
  x.tau_T_s = tr.number_or("tau_T_s", x.tau_T_s, 0.0, 1e9);
  x.tau_eps_s = tr.number_or("tau_eps_s", x.tau_eps_s, 0.0, 1e9);
  x.nodes = static_cast<int>(tr.count_or("nodes", x.nodes, 2, kMaxTensionNodes));
  x.steps = static_cast<int>(tr.count_or("steps", x.steps, 1, kMaxTensionSteps));
  if (static_cast<double>(x.nodes) * x.steps > kMaxTensionWork)
    tr.fail(tr.has("steps") ? "steps" : "nodes", "nodes x steps exceeds the work cap " +
                                                   std::to_string(kMaxTensionWork) + " (README, work caps)");
  return x;
}

// [life] beyond_tests, or its older spelling damage_hold (true = hold, false = extrapolate); both given
// must agree.
LifeSpec::BeyondTests parse_beyond_tests(Reader& lr) {
  using B = LifeSpec::BeyondTests;
  const std::optional<bool> hold = lr.boolean("damage_hold");
  const std::optional<B> old = hold ? std::optional<B>(*hold ? B::hold : B::extrapolate) : std::nullopt;
  const std::optional<std::string> word = lr.string("beyond_tests");
  if (!word) return old.value_or(B::hold);
  B policy = B::hold;
  if (*word == "extrapolate") policy = B::extrapolate;
  else if (*word == "refuse") policy = B::refuse;
  else if (*word != "hold")
    lr.fail("beyond_tests", "beyond_tests must be \"hold\", \"extrapolate\" or \"refuse\", not \"" + *word + "\"");
  if (old && *old != policy)
    lr.fail("beyond_tests", "beyond_tests = \"" + *word + "\" contradicts damage_hold = " + (*hold ? "true" : "false") +
                                " (its older spelling): give one of them");
  return policy;
}

LifeSpec parse_life(const toml::table& t, const std::filesystem::path& base, const std::string& source) {
  Reader lr(t, "life", source);
  lr.allow({"fidelity", "card", "cycles", "crack_sweep_deg", "diagnose_failure", "damage_hold", "beyond_tests",
            "elastic_amplitude", "uncertainty", "samples", "seed"});
  LifeSpec l;
  if (auto f = lr.string("fidelity")) {
    const toml::source_position at = t.get("fidelity")->source().begin;
    l.fidelity = core::fidelity_from_string(*f, "life.fidelity", source, static_cast<int>(at.line),
                                            static_cast<int>(at.column));
  }
  if (auto c = card_file(lr, "card", base)) l.card = *c;
  l.cycles = static_cast<int>(lr.count_or("cycles", l.cycles, 1, 1e4));
  l.crack_sweep_deg = lr.number("crack_sweep_deg", 0.0, 90.0);
  l.diagnose_failure = lr.boolean("diagnose_failure").value_or(false);
  l.beyond_tests = parse_beyond_tests(lr);
  if (auto a = lr.string("elastic_amplitude")) {
    using A = LifeSpec::ElasticAmplitude;
    if (*a == "small") l.elastic_amplitude = A::small;
    else if (*a == "reached") l.elastic_amplitude = A::role;
    else if (*a == "element") l.elastic_amplitude = A::element;
    else
      lr.fail("elastic_amplitude", "elastic_amplitude must be \"element\", \"reached\" or \"small\", not \"" + *a +
                                       "\"");
  }
  if (auto u = lr.string("uncertainty")) {
    if (*u != "constants" && *u != "cards" && *u != "constants+cards")
      lr.fail("uncertainty", "uncertainty must be \"constants\", \"cards\" or \"constants+cards\", not \"" + *u +
                                 "\"");
    l.uncertainty_combined = *u == "constants+cards";
    l.uncertainty_cards = *u == "cards" || l.uncertainty_combined;
  }
  l.samples = static_cast<int>(lr.count_or("samples", l.samples, 2, 1e5));
  l.seed = static_cast<std::uint64_t>(lr.count_or("seed", static_cast<double>(l.seed), 0, 9007199254740992.0));
  lr.finish();
  return l;
}

// [thermal]: the heat balance's coefficients, each over its documented default (docs/thermal.md §3).
belt::ThermalOptions parse_thermal(const toml::table& t, const std::string& source) {
  Reader r(t, "thermal", source);
  r.allow({"convection_W_m2K", "contact_W_m2K", "pulley_C", "rubber_conductivity_W_mK", "specific_heat_J_kgC",
           "friction_to_belt", "loss_angle_deg", "max_temperature_C"});
  belt::ThermalOptions o;
  o.convection_W_m2K = r.number_or("convection_W_m2K", o.convection_W_m2K, 0.0, 1e6, true);
  o.contact_W_m2K = r.number_or("contact_W_m2K", o.contact_W_m2K, 0.0, 1e7);
  o.pulley_C = r.number_or("pulley_C", o.pulley_C, -273.15, 1000.0);
  o.rubber_conductivity_W_mK = r.number_or("rubber_conductivity_W_mK", o.rubber_conductivity_W_mK, 0.0, 1e3, true);
  o.specific_heat_J_kgC = r.number_or("specific_heat_J_kgC", o.specific_heat_J_kgC, 0.0, 1e5, true);
  o.friction_to_belt = r.number_or("friction_to_belt", o.friction_to_belt, 0.0, 1.0);
  o.loss_angle_deg = r.number_or("loss_angle_deg", o.loss_angle_deg, 0.0, 90.0, true);
  o.max_temperature_C = r.number_or("max_temperature_C", o.max_temperature_C, -273.15, 1e4);
  r.finish();
  return o;
}

void parse_flags(Reader& top, const char* table, const std::vector<std::string>& names,
                 std::map<std::string, bool>& out, const std::string& source) {
  if (const toml::table* t = top.table(table)) {
    Reader fr(*t, table, source);
    for (const auto& n : names)
      if (auto b = fr.boolean(n)) out[n] = *b;
    fr.finish();
  }
}

}  // namespace

const char* to_string(LifeSpec::BeyondTests policy) {
  switch (policy) {
    case LifeSpec::BeyondTests::hold: return "hold";
    case LifeSpec::BeyondTests::extrapolate: return "extrapolate";
    case LifeSpec::BeyondTests::refuse: return "refuse";
  }
  return "hold";
}

toml::table parse_scene_toml(const std::string& text, const std::string& source) {
  core::check_toml_limits(text, source);
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InputError(std::string(e.description()) + core::wrong_kind_hint(text, core::FileKind::toml), source,
                     static_cast<int>(e.source().begin.line),
                     static_cast<int>(e.source().begin.column));
  }
}

Scene parse_scene(const std::string& text, const std::string& source) {
  return parse_scene_table(parse_scene_toml(text, source), source);
}

Scene parse_scene_table(const toml::table& root, const std::string& source) {
  Scene s;
  s.path = source;
  const std::filesystem::path base = std::filesystem::path(source).parent_path();
  Reader top(root, "", source);
  top.allow({"name", "drive", "belt", "conditions", "effects", "outputs", "accumulation", "cvt",
             "tension_test", "segment", "life", "thermal"});
  s.name = top.string("name").value_or(std::filesystem::path(source).stem().string());
  parse_drive(s, top, root, source);
  parse_belt(s, top, base, source);
  if (const toml::table* ct = top.table("conditions")) {
    Reader cr(*ct, "conditions", source);
    cr.allow({"temperature_C", "friction", "ambient_C"});
    s.temperature_C = cr.number_or("temperature_C", 20.0, -273.15, 1000.0);
    s.friction = cr.number_or("friction", 0.8, 0.0, 100.0);
    s.ambient_C = cr.number("ambient_C", -273.15, 1000.0);
    cr.finish();
  }
  parse_flags(top, "effects", effect_names(), s.effects, source);
  parse_flags(top, "outputs", output_names(), s.outputs, source);
  if (!top.has("outputs")) s.outputs["load_history"] = true;
  if (const toml::table* at = top.table("accumulation")) s.accumulation = parse_accumulation(*at, source);
  if (const toml::table* vt = top.table("cvt")) s.cvt = parse_cvt(*vt, source);
  if (const toml::table* tt = top.table("tension_test")) s.tension_test = parse_tension_test(*tt, source);
  if (const toml::table* st = top.table("segment")) s.segment = parse_segment(s, *st, source);
  if (const toml::table* lt = top.table("life")) s.life = parse_life(*lt, base, source);
  if (const toml::table* ht = top.table("thermal")) s.thermal = parse_thermal(*ht, source);
  const auto heat = s.effects.find("heat_buildup");
  if (heat != s.effects.end() && heat->second && !s.ambient_C)
    top.fail("conditions.ambient_C", "[effects] heat_buildup = true needs [conditions] ambient_C, the air's temperature the "
                           "belt's heat balance starts from (docs/thermal.md)");
  if (s.ambient_C) s.thermal.ambient_C = *s.ambient_C;
  top.finish();
  return s;
}

Scene load_scene(const std::string& path) { return parse_scene(core::read_file(path), path); }

}  // namespace fitlib::scene
