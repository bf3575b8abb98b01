// The planner's effect registry: each effect declared once, needs before use, every output and
// [effects] key served; the plan's status comes from the registry's logic, not from reason text.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "fitlib/core/io.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/registry.hpp"
#include "fitlib/scene/scene.hpp"

using namespace fitlib;

namespace {
const std::string kData = FITLIB_TEST_DATA_DIR "/scenes/";

const scene::EffectReport& report(const scene::Plan& p, const std::string& name) {
  auto it = std::find_if(p.effects.begin(), p.effects.end(), [&](const auto& e) { return e.name == name; });
  EXPECT_NE(it, p.effects.end()) << name;
  return *it;
}
}  // namespace

TEST(Registry, EachEffectOnceWithItsNeedsEarlierAndEveryKeyServed) {
  const auto& reg = scene::effect_registry();
  std::set<std::string> seen, outputs, keys;
  // Both fidelity branches of the scene-dependent needs.
  auto beam = scene::load_scene(kData + "minimal.toml");
  auto segment = beam;
  segment.life = scene::LifeSpec{};
  segment.life->fidelity = core::Fidelity::elastic;
  for (const auto& e : reg) {
    EXPECT_TRUE(seen.insert(e.name).second) << "declared twice: " << e.name;
    EXPECT_FALSE(e.produces.empty()) << e.name;
    EXPECT_FALSE(e.cost.empty()) << e.name;
    for (const auto* s : {&beam, &segment})
      for (const auto& need : e.needs(*s)) EXPECT_TRUE(seen.count(need)) << e.name << " needs " << need << " before it";
    EXPECT_EQ(e.refines.empty(), e.load_cycle_switch == nullptr) << e.name;
    EXPECT_TRUE(e.run || e.unavailable) << e.name;
    outputs.insert(e.outputs.begin(), e.outputs.end());
    if (!e.effects_key.empty()) keys.insert(e.effects_key);
  }
  for (const auto& o : scene::output_names()) EXPECT_TRUE(outputs.count(o)) << "no effect serves output " << o;
  for (const auto& k : scene::effect_names()) EXPECT_TRUE(keys.count(k)) << "no effect serves [effects] " << k;
}

TEST(Registry, StatusComesFromTheRegistryNotTheReasonText) {
  auto s = scene::load_scene(kData + "minimal.toml");
  // A refinement listed true with no output that uses the load cycle.
  s.outputs = {{"cvt_thrust", true}};
  s.effects = {{"inertia", true}};
  auto p = scene::make_plan(s);
  EXPECT_EQ(report(p, "inertia").status, scene::EffectStatus::not_needed);
  EXPECT_FALSE(p.will_run("inertia"));
  EXPECT_FALSE(p.will_run("contact_arcs"));
  EXPECT_TRUE(p.will_run("drive"));
  EXPECT_FALSE(p.load_cycle.inertia);
  // A life at a segment level: the segment FE and fatigue run on the load cycle, the beam level not.
  s.outputs = {{"life", true}};
  s.life = scene::LifeSpec{};
  s.life->fidelity = core::Fidelity::elastic;
  p = scene::make_plan(s);
  EXPECT_EQ(report(p, "segment_fe").status, scene::EffectStatus::run);
  EXPECT_EQ(report(p, "fatigue").status, scene::EffectStatus::run);
  EXPECT_FALSE(p.will_run("beam_stresses"));
  EXPECT_TRUE(p.will_run("contact_arcs"));
  EXPECT_TRUE(p.unavailable_outputs.empty());
  // The same scene at the beam level: load cycle, beam stresses and fatigue run, and nothing else
  // beyond stiffness and drive.
  s.life->fidelity = core::Fidelity::beam;
  s.effects.clear();
  p = scene::make_plan(s);
  for (const auto& e : p.effects) {
    const bool expected = e.name == "stiffness" || e.name == "drive" || e.name == "contact_arcs" ||
                          e.name == "beam_stresses" || e.name == "fatigue";
    EXPECT_EQ(p.will_run(e.name), expected) << e.name << ": " << e.reason;
  }
  EXPECT_EQ(report(p, "beam_stresses").reason, "needed by fatigue");
  EXPECT_EQ(report(p, "fatigue").reason, "needed by life");
}
