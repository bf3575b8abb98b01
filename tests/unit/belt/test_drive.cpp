// Drive geometry, tensions and the load cycle around the drive.
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/belt/drive.hpp"
#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/belt/stiffness.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"

using namespace fitlib::belt;
using fitlib::core::InputError;
using fitlib::core::kPi;

namespace {
Pulley pulley(const char* name, double d_mm, PulleyRole role, double x = 0, double y = 0) {
  Pulley p;
  p.name = name;
  p.pitch_radius_mm = d_mm / 2;
  p.role = role;
  p.x_mm = x;
  p.y_mm = y;
  return p;
}

DriveCase reference_drive(double torque_Nm, double slack_N = 300.0, double rpm = 3000.0) {
  DriveCase c;
  c.geometry = make_two_pulley_geometry(pulley("driver", 100, PulleyRole::driver),
                                        pulley("driven", 100, PulleyRole::driven), 300.0);
  c.span_tension_N = span_tensions(c.geometry, {torque_Nm, TensionRule::slack, slack_N});
  c.friction = 0.8;
  c.belt_speed_mm_s = rpm * 2 * kPi / 60 * 50.0;
  const double T = 80.0;
  c.belt.c_N = cord_stiffness_N(T);
  c.belt.EI_Nmm2 = bending_stiffness_Nmm2(T);
  c.belt.k1_MPa = radial_stiffness_MPa(c.belt.wedge_half_angle_rad, axial_modulus_MPa(T),
                                       c.belt.height_mm, c.belt.width_mm);
  return c;
}

template <typename F>
std::string error_key(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.key();
  }
  return "<no error>";
}
}  // namespace

TEST(DriveGeometry, OpenTwoPulleyDriveClosedForm) {
  const double r1 = 40, r2 = 90, a = 400;
  auto g = make_two_pulley_geometry(pulley("drv", 2 * r1, PulleyRole::driver),
                                    pulley("dvn", 2 * r2, PulleyRole::driven), a);
  const double small_wrap = kPi - 2 * std::asin((r2 - r1) / a);
  EXPECT_NEAR(g.wrap_rad[0], small_wrap, 1e-12);
  EXPECT_NEAR(g.wrap_rad[1], 2 * kPi - small_wrap, 1e-12);
  const double span = std::sqrt(a * a - (r2 - r1) * (r2 - r1));
  EXPECT_NEAR(g.spans[0].length_mm, span, 1e-12);
  // Classic open-belt length L = 2 span + r1 α1 + r2 α2.
  EXPECT_NEAR(g.belt_length_mm, 2 * span + r1 * small_wrap + r2 * (2 * kPi - small_wrap), 1e-9);
}

TEST(DriveGeometry, ThreePulleyTriangle) {
  // Equal pulleys on an equilateral triangle (CCW): each wrap is 120°.
  const double side = 300, h = side * std::sqrt(3.0) / 2;
  auto g = make_geometry({pulley("a", 80, PulleyRole::driver, 0, 0),
                          pulley("b", 80, PulleyRole::driven, side, 0),
                          pulley("c", 80, PulleyRole::idler, side / 2, h)});
  for (double w : g.wrap_rad) EXPECT_NEAR(w, 2 * kPi / 3, 1e-12);
  EXPECT_NEAR(g.belt_length_mm, 3 * side + 2 * kPi * 40, 1e-9);
  // Clockwise order is rejected with the key of the pulley the belt misses.
  EXPECT_NE(error_key([] {
              make_geometry({pulley("a", 80, PulleyRole::driver, 0, 0),
                             pulley("c", 80, PulleyRole::idler, 150, 259.8),
                             pulley("b", 80, PulleyRole::driven, 300, 0)});
            }),
            "<no error>");
  // Unequal pulleys listed clockwise wrap 720° in all: the message says to list them the other way.
  try {
    make_geometry({pulley("motor", 112, PulleyRole::driver, 0, 0), pulley("fan", 180, PulleyRole::driven, 300, 0),
                   pulley("idler", 70, PulleyRole::idler, 150, -90)});
    ADD_FAILURE() << "a clockwise drive was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "drive.pulleys");
    EXPECT_NE(std::string(e.what()).find("counter-clockwise travel order (they are clockwise)"), std::string::npos)
        << e.what();
  }
}

TEST(DriveGeometry, OverlappingPulleysNameTheKey) {
  EXPECT_EQ(error_key([] {
              make_two_pulley_geometry(pulley("a", 100, PulleyRole::driver),
                                       pulley("b", 100, PulleyRole::driven), 90);
            }),
            "drive.center_distance_mm");
}

TEST(DriveTensions, RulesAndMultiPulleyShares) {
  auto g = make_two_pulley_geometry(pulley("drv", 100, PulleyRole::driver),
                                    pulley("dvn", 200, PulleyRole::driven), 400);
  // 20 N·m on R = 50 mm: ΔF = 400 N.
  auto F = span_tensions(g, {20.0, TensionRule::slack, 100.0});
  EXPECT_DOUBLE_EQ(F[0], 100.0);  // leaves the driver: slack
  EXPECT_DOUBLE_EQ(F[1], 500.0);  // leaves the driven: tight
  F = span_tensions(g, {20.0, TensionRule::initial, 300.0});
  EXPECT_DOUBLE_EQ(F[0], 100.0);
  EXPECT_DOUBLE_EQ(F[1], 500.0);
  F = span_tensions(g, {20.0, TensionRule::tight, 500.0});
  EXPECT_DOUBLE_EQ(F[0], 100.0);
  EXPECT_EQ(error_key([&] { span_tensions(g, {20.0, TensionRule::initial, 100.0}); }),
            "drive.initial_tension_N");
  // A slack span of exactly 0 N is a tension (the tension test needs no pressing span); the load
  // cycle refuses it under the key the scene gave (LoadCycle.HardCasesGiveResultsOrClearErrors).
  EXPECT_EQ(span_tensions(g, {20.0, TensionRule::initial, 200.0})[0], 0.0);
  EXPECT_STREQ(tension_key(TensionRule::initial), "drive.initial_tension_N");
}

TEST(LoadCycle, ReferenceDriveZonesAndContinuity) {
  auto c = reference_drive(15.0);
  auto lc = compute_load_cycle(c);
  ASSERT_EQ(lc.pulleys.size(), 2u);
  EXPECT_EQ(lc.pulleys[0].name, "driven");  // the cycle starts on the slack side
  EXPECT_NEAR(lc.cycle_length_mm, c.geometry.belt_length_mm, 1e-9);
  const double F1 = c.span_tension_N[0], F2 = c.span_tension_N[1];
  for (const auto& x : lc.samples) {
    EXPECT_TRUE(std::isfinite(x.F_N) && std::isfinite(x.p_MPa) && std::isfinite(x.K_1_mm) &&
                std::isfinite(x.gamma_rad) && std::isfinite(x.slide_mm_s));
    EXPECT_GE(x.F_N, F1 - 1e-9);
    EXPECT_LE(x.F_N, F2 + 1e-9);
    EXPECT_LE(x.K_1_mm, 1.0 / 50.0 + 1e-12);
    if (x.zone == Zone::non_sliding) {
      EXPECT_DOUBLE_EQ(x.gamma_rad, kPi);
    }
  }
  // Sliding arcs end at the outgoing span force.
  for (const auto& p : lc.pulleys) {
    EXPECT_GT(p.sliding_rad, 0.0);
    EXPECT_GT(p.non_sliding_rad, 0.0);
    EXPECT_NEAR(p.phi_C_in_rad + p.phi_E_in_rad + p.non_sliding_rad + p.sliding_rad +
                    p.phi_E_out_rad + p.phi_C_out_rad, p.wrap_rad, 1e-12);
  }
  // Force rises monotonically over the driven pulley's sliding arc and falls on the driver's.
  double last_driven = 0, last_driver = 1e300;
  for (const auto& x : lc.samples) {
    if (x.zone != Zone::sliding) continue;
    if (x.pulley == 1) { EXPECT_GE(x.F_N, last_driven - 1e-9); last_driven = x.F_N; }
    if (x.pulley == 0) { EXPECT_LE(x.F_N, last_driver + 1e-9); last_driver = x.F_N; }
  }
  // The entrance zone's curvature meets the free span's at the contact point and reaches 1/R.
  for (std::size_t k = 1; k < lc.samples.size(); ++k) {
    const auto& a = lc.samples[k - 1];
    const auto& b = lc.samples[k];
    if (a.zone == Zone::free_span_in && b.zone == Zone::entrance) {
      EXPECT_NEAR(b.K_1_mm * 50.0, ZoneConstants::K0C_in, 1e-12);
    }
  }
}

TEST(LoadCycle, PressureIsRadialEquilibriumInNonSlidingArc) {
  auto c = reference_drive(10.0);
  c.belt.density_kg_m3 = 0.0;
  auto lc = compute_load_cycle(c);
  const double beta = c.belt.wedge_half_angle_rad;
  for (const auto& x : lc.samples)
    if (x.zone == Zone::non_sliding) {
      EXPECT_NEAR(x.p_MPa, x.F_N * std::cos(beta) /
                               (2 * c.belt.height_mm * 50.0 * (std::sin(beta) + 0.8 * std::cos(beta))),
                  1e-12);
    }
}

TEST(LoadCycle, ClosedFormsAndOdeGiveNearlyTheSameCycle) {
  auto c = reference_drive(15.0);
  LoadCycleOptions ode;
  ode.effects.full_ode = true;
  auto a = compute_load_cycle(c), b = compute_load_cycle(c, ode);
  // Driven arc within 2 %; the driver's closed form is shorter (docs/belt.md), within 40 %.
  EXPECT_NEAR(a.pulleys[0].sliding_rad, b.pulleys[0].sliding_rad, 0.02 * b.pulleys[0].sliding_rad);
  EXPECT_NEAR(a.pulleys[1].sliding_rad, b.pulleys[1].sliding_rad, 0.4 * b.pulleys[1].sliding_rad);
}

TEST(LoadCycle, CentrifugalTensionIsSuperimposedAndLiftOffIsAnError) {
  auto c = reference_drive(10.0, 300.0, 3000.0);
  auto lc = compute_load_cycle(c);
  const double V_m_s = c.belt_speed_mm_s / 1000;
  EXPECT_NEAR(lc.centrifugal_tension_N, 1200.0 * c.belt.area_mm2 * 1e-6 * V_m_s * V_m_s, 1e-9);
  auto fast = reference_drive(10.0, 300.0, 30000.0);
  try {
    compute_load_cycle(fast);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lifts off"), std::string::npos);
  }
}

TEST(LoadCycle, HardCasesGiveResultsOrClearErrors) {
  // Severe load: the belt slips (error names the torque). μ = 0.3: capstan limit exp(μπ/sin β) = 18.
  auto severe = reference_drive(400.0);
  severe.friction = 0.3;
  EXPECT_EQ(error_key([&] { compute_load_cycle(severe); }), "drive.torque_Nm");
  // The first torque that slips needs a tension ratio below the capstan limit: the message says the
  // limit holds for a radially rigid belt only (a user read "ratio 8 needs more than 169 deg, capstan
  // limit 125" as a contradiction).
  for (double torque = 10.0;; torque += 10.0) {
    ASSERT_LT(torque, 1000.0);
    std::string message;
    auto d = reference_drive(torque);
    d.friction = 0.5;  // the bundled drives' (capstan limit 124)
    try {
      compute_load_cycle(d);
      continue;
    } catch (const InputError& e) {
      message = e.what();
    }
    ASSERT_NE(message.find("belt slips"), std::string::npos) << message;
    const double ratio = std::stod(message.substr(message.find("tension ratio ") + 14));
    const double limit = std::stod(message.substr(message.find("beta) = ") + 8));
    EXPECT_LT(ratio, limit) << message;
    EXPECT_NE(message.find("holds for a radially rigid belt only: with c0 = "), std::string::npos) << message;
    break;
  }
  // Zero slack tension.
  EXPECT_EQ(error_key([] { compute_load_cycle(reference_drive(10.0, 0.0, 0.0)); }),
            "drive.slack_tension_N");
  auto from_initial = reference_drive(10.0, 0.0, 0.0);  // the key the scene's rule came from
  from_initial.tension_key = tension_key(TensionRule::initial);
  EXPECT_EQ(error_key([&] { compute_load_cycle(from_initial); }), "drive.initial_tension_N");
  // μ → 0 cannot transmit torque; with no torque it runs.
  auto c = reference_drive(10.0);
  c.friction = 0.0;
  EXPECT_EQ(error_key([&] { compute_load_cycle(c); }), "drive.torque_Nm");
  try {  // and says why: raising the tension would not help
    compute_load_cycle(c);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("without friction (conditions.friction = 0)"), std::string::npos) << e.what();
  }
  auto idle = reference_drive(0.0);
  idle.friction = 0.0;
  EXPECT_NO_THROW(compute_load_cycle(idle));
  // Self-locking μ.
  c.friction = 5.0;
  EXPECT_EQ(error_key([&] { compute_load_cycle(c); }), "conditions.friction");
  // EI → 0: zones vanish, curvature jumps, no NaN.
  auto limp = reference_drive(10.0);
  limp.belt.EI_Nmm2 = 0.0;
  auto lc = compute_load_cycle(limp);
  EXPECT_EQ(lc.pulleys[0].phi_E_in_rad, 0.0);
  for (const auto& x : lc.samples) EXPECT_TRUE(std::isfinite(x.K_1_mm) && std::isfinite(x.p_MPa));
  // Small wrap angle with a stiff belt: the zones do not fit.
  auto tiny = reference_drive(1.0);
  tiny.geometry = make_geometry({pulley("a", 100, PulleyRole::driver, 0, 0),
                                 pulley("b", 100, PulleyRole::driven, 2000, 0),
                                 pulley("c", 20, PulleyRole::idler, 1000, 45)});
  tiny.span_tension_N = span_tensions(tiny.geometry, {1.0, TensionRule::slack, 300.0});
  tiny.belt.EI_Nmm2 = 2e4;
  const std::string key = error_key([&] { compute_load_cycle(tiny); });
  EXPECT_EQ(key.rfind("drive.pulleys[2]", 0), 0u) << key;
}

TEST(LoadCycle, EffectsSwitchOff) {
  auto c = reference_drive(15.0);
  LoadCycleOptions o;
  o.effects.bending_zones = false;
  o.effects.inertia = false;
  auto lc = compute_load_cycle(c, o);
  EXPECT_EQ(lc.centrifugal_tension_N, 0.0);
  for (const auto& x : lc.samples) {
    EXPECT_NE(x.zone, Zone::entrance);
    EXPECT_NE(x.zone, Zone::exit);
    if (x.zone == Zone::free_span_in || x.zone == Zone::free_span_out) {
      EXPECT_EQ(x.K_1_mm, 0.0);
    }
  }
}

TEST(LoadCycle, DriverExitRampGoesFullZeroFull) {
  auto c = reference_drive(15.0);
  auto lc = compute_load_cycle(c);
  double min_used = 1e9;
  for (const auto& x : lc.samples)
    if (x.zone == Zone::exit && x.pulley == 0) min_used = std::min(min_used, x.friction_used);
  EXPECT_LT(min_used, 0.1 * c.friction);
}

TEST(Stiffness, FritzsonTemperatureLaws) {
  EXPECT_NEAR(cord_stiffness_N(102.0), 5.0 * 100.0 * 76.6, 1e-9);
  EXPECT_NEAR(axial_modulus_MPa(95.5), 10.0 * 12.75, 1e-12);
  EXPECT_NEAR(bending_stiffness_Nmm2(20.0), 8340.0, 1e-9);
  EXPECT_NEAR(radial_stiffness_MPa(kPi / 4, 100.0, 6.0, 12.0), 500.0, 1e-9);
}
