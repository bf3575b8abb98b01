// Life effects of a scene (docs/fatigue.md "Life of a scene"): the fidelity level, the stress
// histories at the monitored points (beam level; the segment levels once they land) and the
// fatigue life on them.
#include "effects.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/fatigue/card.hpp"

namespace fitlib::scene {
namespace detail {
namespace {

// What the life took from a material card, read off the stiffness sources.
std::string card_use(const Scene& s, const SceneResult& r, const std::string& role) {
  const std::string path = s.materials.at(role);
  std::string use;
  auto add = [&](const std::string& source, const char* what) {
    if (source.rfind("card " + path, 0) == 0) use += (use.empty() ? "" : ", ") + std::string(what);
  };
  if (r.stiffness) {
    add(r.stiffness->c_source, "cord stiffness c");
    add(r.stiffness->k1_source, "radial stiffness k1");
    add(r.stiffness->EI_source, "bending stiffness EI (and the beam level's layer moduli EI/I)");
  }
  if (use.empty()) use = "not read at fidelity " + r.plan.life->fidelity;
  return use;
}

InputFile file_input(const std::string& role, const std::string& path, const std::string& use) {
  return {role, path, core::sha256_hex(core::read_file(path)), use};
}

}  // namespace

std::optional<std::string> segment_levels_unavailable() {
  return std::string("not available yet: the segment's run of the load history (elastic and "
                     "complete levels, issue 11) has not landed; use [life] fidelity = \"beam\"");
}

void beam_stresses(const Scene& s, SceneResult& r) {
  in_scene(s, [&] {
    const fatigue::BeamSection section = fatigue::default_beam_section(*r.drive, s.temperature_C);
    r.stresses = fatigue::beam_stress_histories(*r.cycle, *r.drive, section);
    r.life_conditions = fatigue::cycle_conditions(*r.cycle, *r.drive, s.temperature_C);
  });
}

void fatigue_life(const Scene& s, SceneResult& r) {
  const LifeSpec spec = s.life.value_or(LifeSpec{});
  LifeResult life;
  life.plan = *r.plan.life;
  const char* constants = "life constants of (6.31) per mode";
  fatigue::FatigueCard card;
  if (spec.card.empty()) {
    card = fatigue::default_card();
    life.inputs.push_back({"fatigue", "built-in: fatigue::default_card() = datasets/cards/fatigue-fritzson-1988.json",
                           core::sha256_hex(fatigue::card_to_json(card).dump(2) + "\n"), constants});
  } else {
    card = fatigue::load_card(spec.card);
    life.inputs.push_back(file_input("fatigue", spec.card, constants));
  }
  if (spec.crack_sweep_deg) card.crack_sweep_deg = *spec.crack_sweep_deg;
  for (const char* role : {"bottom", "cushion", "cord"})
    if (s.materials.count(role)) life.inputs.push_back(file_input(role, s.materials.at(role), card_use(s, r, role)));
  life.report = in_scene(s, [&] { return fatigue::evaluate_life(*r.stresses, card, *r.life_conditions); });
  r.life = std::move(life);
}

}  // namespace detail

LifePlan choose_life_plan(const Scene& s) {
  if (s.life && s.life->fidelity) return {*s.life->fidelity, "[life] fidelity = " + *s.life->fidelity};
  const bool cards = s.materials.count("bottom") && s.materials.count("cushion");
  if (!cards && !s.segment)
    return {"beam", "default: the scene gives neither bottom and cushion cards nor a [segment] table"};
  const std::string finest = cards ? "complete" : "elastic";
  const std::string why = cards ? "the scene gives bottom and cushion cards" : "the scene has a [segment] table";
  if (detail::segment_levels_unavailable())
    return {"beam", "default: " + finest + " (" + why + ") is not available yet, so beam"};
  return {finest, "default: " + why};
}

}  // namespace fitlib::scene
