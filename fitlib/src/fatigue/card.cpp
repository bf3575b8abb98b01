#include "fitlib/fatigue/card.hpp"

#include <cmath>
#include <set>

#include <boost/algorithm/string/join.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/json.hpp"

namespace fitlib::fatigue {

using nlohmann::json;

const char* to_string(Mode mode) {
  return mode == Mode::radial_crack ? "radial_crack" : "separation";
}

std::optional<Mode> mode_from_string(const std::string& text) {
  if (text == "radial_crack") return Mode::radial_crack;
  if (text == "separation") return Mode::separation;
  return std::nullopt;
}

namespace detail {
extern const char* const kDefaultCardJson;  // generated from the bundled card (CMakeLists.txt)
}

FatigueCard default_card() {
  static const FatigueCard card = card_from_json(
      core::parse_json(detail::kDefaultCardJson, "built-in fatigue card"), "built-in fatigue card");
  return card;
}

FatigueCard card_at_level(const FatigueCard& card, core::Fidelity fidelity) {
  FatigueCard c = card;
  c.levels.clear();
  const auto level = card.levels.find(fidelity);
  if (level == card.levels.end()) return c;
  for (Mode m : {Mode::radial_crack, Mode::separation}) {
    const std::optional<core::Fidelity>& of = card.law(m).stress_fidelity;
    if (!of || *of == fidelity) continue;
    // A level's law is the mode's with n and b held and σ0 calibrated (scripts/calibrate-levels.sh):
    // where it states no scatter or covariance it keeps the mode's, the belts' scatter about the law.
    LifeLaw law = level->second.law(m);
    if (!law.scatter) law.scatter = card.law(m).scatter;
    if (!law.covariance) law.covariance = card.law(m).covariance;
    c.law(m) = law;
  }
  return c;
}

namespace {

json law_json(const LifeLaw& l) {
  json j = {{"sigma0_MPa", l.sigma0_MPa}, {"n", l.n}, {"b_per_C", l.b_per_C}};
  if (l.stress_fidelity) j["stress_fidelity"] = core::to_string(*l.stress_fidelity);
  if (l.scatter)
    j["scatter"] = {{"distribution", l.scatter->distribution}, {"sigma_log10", l.scatter->sigma_log10},
                    {"dof", l.scatter->dof}};
  if (l.covariance) j["covariance"] = {{"parameters", {"ln_sigma0", "n", "b_per_C"}}, {"matrix", *l.covariance}};
  return j;
}

// Reads one object with exactly the keys `allowed`; each value a finite number unless listed in
// `other`.
class Reader {
 public:
  Reader(const json& j, std::string source, std::string path, std::set<std::string> allowed)
      : j_(j), source_(std::move(source)), path_(std::move(path)) {
    if (!j_.is_object()) throw core::InputError("expected an object", source_, 0, 0, path_);
    for (const auto& item : j_.items())
      if (!allowed.count(item.key()))
        throw core::InputError("unknown key; this object takes " + boost::algorithm::join(allowed, ", "), source_, 0, 0,
                               key(item.key()));
  }
  std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
  bool has(const std::string& k) const { return j_.contains(k); }
  const json& at(const std::string& k) const {
    if (!j_.contains(k)) throw core::InputError("missing required key", source_, 0, 0, key(k));
    return j_.at(k);
  }
  // A finite number in [lo, hi] (exclusive where `open`).
  double number(const std::string& k, double lo, double hi, bool open = false) const {
    const json& v = at(k);
    if (!v.is_number()) throw core::InputError("expected a number", source_, 0, 0, key(k));
    const double x = v.get<double>();
    const bool below = open ? x <= lo : x < lo;
    if (!std::isfinite(x) || below || x > hi)
      throw core::InputError("value " + v.dump() + " out of range", source_, 0, 0, key(k));
    return x;
  }
  std::string text(const std::string& k) const {
    const json& v = at(k);
    if (!v.is_string()) throw core::InputError("expected a string", source_, 0, 0, key(k));
    return v.get<std::string>();
  }
  const std::string& source() const { return source_; }

 private:
  const json& j_;
  std::string source_, path_;
};

constexpr double kHuge = 1e300;

LifeScatter read_scatter(const Reader& law) {
  Reader r(law.at("scatter"), law.source(), law.key("scatter"), {"distribution", "sigma_log10", "dof"});
  LifeScatter sc;
  sc.distribution = r.text("distribution");
  if (sc.distribution != "lognormal")
    throw core::InputError("'" + sc.distribution + "' is not a scatter distribution this version reads (lognormal)",
                           law.source(), 0, 0, r.key("distribution"));
  sc.sigma_log10 = r.number("sigma_log10", 0.0, 10.0);
  sc.dof = static_cast<int>(r.number("dof", 1.0, 1e9));
  return sc;
}

// A symmetric 3 x 3 matrix over (ln σ0, n, b) with a non-negative diagonal.
LawCovariance read_covariance(const Reader& law) {
  Reader r(law.at("covariance"), law.source(), law.key("covariance"), {"parameters", "matrix"});
  const json& names = r.at("parameters");
  if (names != json({"ln_sigma0", "n", "b_per_C"}))
    throw core::InputError("expected [\"ln_sigma0\", \"n\", \"b_per_C\"]", law.source(), 0, 0, r.key("parameters"));
  const json& m = r.at("matrix");
  const std::string key = r.key("matrix");
  if (!m.is_array() || m.size() != 3) throw core::InputError("expected a 3 x 3 array", law.source(), 0, 0, key);
  LawCovariance c{};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!m[i].is_array() || m[i].size() != 3) throw core::InputError("expected a 3 x 3 array", law.source(), 0, 0, key);
    for (std::size_t k = 0; k < 3; ++k) {
      if (!m[i][k].is_number() || !std::isfinite(m[i][k].get<double>()))
        throw core::InputError("expected finite numbers", law.source(), 0, 0, key);
      c[i][k] = m[i][k].get<double>();
    }
  }
  for (std::size_t i = 0; i < 3; ++i) {
    if (c[i][i] < 0.0) throw core::InputError("a negative variance on the diagonal", law.source(), 0, 0, key);
    for (std::size_t k = 0; k < i; ++k)
      if (std::abs(c[i][k] - c[k][i]) > 1e-12 * (std::abs(c[i][k]) + std::abs(c[k][i])))
        throw core::InputError("the covariance is not symmetric", law.source(), 0, 0, key);
  }
  return c;
}

LifeLaw read_law(const Reader& modes, const std::string& name) {
  Reader r(modes.at(name), modes.source(), modes.key(name),
           {"sigma0_MPa", "n", "b_per_C", "stress_fidelity", "scatter", "covariance"});
  LifeLaw law{r.number("sigma0_MPa", 0.0, kHuge, true), r.number("n", 0.0, 1000.0, true),
              r.number("b_per_C", -10.0, 10.0), std::nullopt};
  if (r.has("stress_fidelity"))
    law.stress_fidelity =
        core::fidelity_from_string(r.text("stress_fidelity"), r.key("stress_fidelity"), modes.source());
  if (r.has("scatter")) law.scatter = read_scatter(r);
  if (r.has("covariance")) law.covariance = read_covariance(r);
  return law;
}

// "levels": {"beam": {"radial_crack": {...}, "separation": {...}}, ...}; a law's stated level must
// be its key's (absent: the key's).
std::map<core::Fidelity, LevelLaws> read_levels(const Reader& card) {
  Reader levels(card.at("levels"), card.source(), "levels", {"beam", "elastic", "complete"});
  std::map<core::Fidelity, LevelLaws> out;
  for (core::Fidelity fidelity : {core::Fidelity::beam, core::Fidelity::elastic, core::Fidelity::complete}) {
    const char* level = core::to_string(fidelity);
    if (!levels.has(level)) continue;
    Reader modes(levels.at(level), card.source(), levels.key(level), {"radial_crack", "separation"});
    LevelLaws laws{read_law(modes, "radial_crack"), read_law(modes, "separation")};
    for (Mode m : {Mode::radial_crack, Mode::separation}) {
      std::optional<core::Fidelity>& of = laws.law(m).stress_fidelity;
      if (of && *of != fidelity)
        throw core::InputError(std::string("stress_fidelity '") + core::to_string(*of) + "' under levels." + level +
                                   " (a level's constants are for its own stresses)",
                               card.source(), 0, 0, modes.key(std::string(to_string(m)) + ".stress_fidelity"));
      of = fidelity;
    }
    out.emplace(fidelity, laws);
  }
  return out;
}

}  // namespace

json card_to_json(const FatigueCard& c) {
  json j = {{"schema", FatigueCard::kSchema},
            {"name", c.name},
            {"reference_temperature_C", c.reference_temperature_C},
            {"crack_sweep_deg", c.crack_sweep_deg},
            {"modes", {{"radial_crack", law_json(c.radial_crack)},
                       {"separation", law_json(c.separation)}}},
            {"provenance", c.provenance}};
  for (const auto& [level, laws] : c.levels)
    j["levels"][core::to_string(level)] = {{"radial_crack", law_json(laws.radial_crack)}, {"separation", law_json(laws.separation)}};
  if (c.cord_break) {
    const CordBreakLaw& k = *c.cord_break;
    j["cord_break"] = {{"a", k.a}, {"b_per_MPa", k.b_per_MPa}, {"ultimate_MPa", k.ultimate_MPa},
                       {"cord_area_mm2", k.cord_area_mm2}, {"b_T_per_C", k.b_T_per_C}};
  }
  return j;
}

FatigueCard card_from_json(const json& j, const std::string& source) {
  Reader r(j, source, "",
           {"schema", "name", "reference_temperature_C", "crack_sweep_deg", "modes", "cord_break", "levels",
            "provenance"});
  const std::string schema = r.text("schema");
  if (schema != FatigueCard::kSchema)
    throw core::InputError("unsupported schema '" + schema + "' (expected " +
                               FatigueCard::kSchema + ")", source, 0, 0, "schema");
  FatigueCard c;
  c.name = r.has("name") ? r.text("name") : "";
  c.reference_temperature_C = r.number("reference_temperature_C", -273.15, 1000.0);
  if (r.has("crack_sweep_deg")) c.crack_sweep_deg = r.number("crack_sweep_deg", 0.0, 90.0);
  Reader modes(r.at("modes"), source, "modes", {"radial_crack", "separation"});
  c.radial_crack = read_law(modes, "radial_crack");
  c.separation = read_law(modes, "separation");
  if (r.has("cord_break")) {
    Reader k(r.at("cord_break"), source, "cord_break",
             {"a", "b_per_MPa", "ultimate_MPa", "cord_area_mm2", "b_T_per_C"});
    CordBreakLaw law;
    law.a = k.number("a", -kHuge, kHuge);
    law.b_per_MPa = k.number("b_per_MPa", 0.0, kHuge, true);
    law.ultimate_MPa = k.number("ultimate_MPa", 0.0, kHuge, true);
    law.cord_area_mm2 = k.number("cord_area_mm2", 0.0, kHuge, true);
    if (k.has("b_T_per_C")) law.b_T_per_C = k.number("b_T_per_C", -10.0, 10.0);
    c.cord_break = law;
  }
  if (r.has("levels")) c.levels = read_levels(r);
  if (r.has("provenance")) c.provenance = r.at("provenance");
  return c;
}

FatigueCard load_card(const std::string& path) {
  return card_from_json(core::parse_json(core::read_file(path), path), path);
}

std::string stress_fidelity_warning(const FatigueCard& card, core::Fidelity fidelity) {
  std::string modes, levels;
  for (Mode m : {Mode::radial_crack, Mode::separation}) {
    const std::optional<core::Fidelity>& of = card.law(m).stress_fidelity;
    if (!of || *of == fidelity) continue;
    modes += (modes.empty() ? "" : " and ") + std::string(to_string(m));
    if (levels.find(core::to_string(*of)) == std::string::npos)
      levels += (levels.empty() ? "" : " and ") + std::string(core::to_string(*of));
  }
  if (modes.empty()) return "";
  return "the fatigue card's " + modes + " constants were fitted to " + levels + "-level stresses, and this run's "
         "stresses are the " + core::to_string(fidelity) + " level's: the levels' lives of one drive differ by up to 1000x (docs/fatigue.md §4), "
         "so the life is off the constants' scale; fit the constants to life tests run at this level (fitcli "
         "life-fit) or run the level they were fitted at ([life] fidelity)";
}

void save_card(const std::string& path, const FatigueCard& card) {
  core::write_file_atomically(path, card_to_json(card).dump(2) + "\n");
}

}  // namespace fitlib::fatigue
