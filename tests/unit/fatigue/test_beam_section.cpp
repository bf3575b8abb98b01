#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/beam_section.hpp"

namespace fitlib::fatigue {
namespace {

belt::DriveCase drive() {
  belt::DriveCase d;
  d.belt_speed_mm_s = 10000.0;
  d.belt.c_N = 40000.0;
  d.belt.width_mm = 11.0;
  d.belt.density_kg_m3 = 1000.0;
  d.belt.wedge_half_angle_rad = 0.3;
  return d;
}

belt::LoadCycle one_sample(double F, double K, double p = 0.0, double gamma = 0.0,
                           double mu = 0.0) {
  belt::LoadCycle c;
  belt::LoadSample s;
  s.s_mm = 100.0;
  s.F_N = F;
  s.K_1_mm = K;
  s.p_MPa = p;
  s.gamma_rad = gamma;
  s.friction_used = mu;
  c.samples.push_back(s);
  c.cycle_length_mm = 1000.0;
  return c;
}

BeamSection section() {
  BeamSection s;
  s.bottom_modulus_MPa = 12.0;
  s.cushion_modulus_MPa = 30.0;
  s.poisson = 0.45;
  return s;
}

TEST(BeamSection, StretchAndBendOfTheLayersInClosedForm) {
  BeamSection s = section();
  s.manufactured_curvature_1_mm = 0.004;
  s.gap_stress_concentration = 1.7;
  // F = 800 N → ε = 0.02; K = 1/60 mm⁻¹. No pressure: σ11 = σ12 = 0, σ22 = k_t E ε22/(1 − ν²).
  const auto h = beam_stress_histories(one_sample(800.0, 1.0 / 60.0), drive(), s);
  ASSERT_EQ(h.size(), 2u);
  const double Eg = 12.0 / (1.0 - 0.45 * 0.45), Ec = 30.0 / (1.0 - 0.45 * 0.45);
  const double e_gap = 1.02 * (1.0 - 4.1 / 60.0) / (1.0 - 0.004 * 4.1) - 1.0;
  const double e_cushion = 1.02 * (1.0 - 0.25 / 60.0) / (1.0 - 0.004 * 0.25) - 1.0;
  EXPECT_EQ(h[0].role, Role::bottom);
  EXPECT_DOUBLE_EQ(h[0].y_mm, -4.1);
  // Named points, not scanned FE points (life.json names no element for them).
  EXPECT_EQ(h[0].element, -1);
  EXPECT_EQ(h[1].element, -1);
  EXPECT_NEAR(h[0].samples[0].s22_MPa, 1.7 * Eg * e_gap, 1e-12);
  EXPECT_NEAR(h[1].samples[0].s22_MPa, Ec * e_cushion, 1e-12);
  EXPECT_EQ(h[0].samples[0].s11_MPa, 0.0);
  EXPECT_DOUBLE_EQ(h[0].samples[0].t_s, 0.01);
  // Straight, unloaded, moulded straight: no stress.
  const auto z = beam_stress_histories(one_sample(0.0, 0.0), drive(), section());
  EXPECT_EQ(z[0].samples[0].s22_MPa, 0.0);
  EXPECT_EQ(z[1].samples[0].s22_MPa, 0.0);
}

TEST(BeamSection, PressureFrictionAndInertiaAsBodyForces) {
  // p = 2 MPa, γ = 120°, μ_used = 0.5, K = 1/50: B_l and B_r of (6.6)–(6.7) by hand.
  const double p = 2.0, g = 2.0943951023931953, mu = 0.5, K = 0.02, beta = 0.3, B = 11.0;
  const double bs = std::atan(std::tan(beta) * std::cos(g));
  const double Bl = -mu * p * (2.0 / B) * std::cos(bs) * std::sin(g) / std::cos(beta);
  const double Br = p * (2.0 / B) * (std::sin(beta) - mu * std::cos(bs) * std::cos(g)) / std::cos(beta) +
                    1000.0e-12 * K * 1e8;
  const auto h = beam_stress_histories(one_sample(0.0, K, p, g, mu), drive(), section());
  // Gap bottom: a free surface.
  EXPECT_EQ(h[0].samples[0].s11_MPa, 0.0);
  EXPECT_EQ(h[0].samples[0].s12_MPa, 0.0);
  // Mid-cushion: the load of everything below it, cogs pitch-averaged.
  const double height = 4.1 - 0.25 + 0.51 * 2.5;
  EXPECT_NEAR(h[1].samples[0].s11_MPa, -Br * height, 1e-12);
  EXPECT_NEAR(h[1].samples[0].s12_MPa, Bl * height, 1e-12);
  const double e = (1.0 - K * 0.25) - 1.0;
  EXPECT_NEAR(h[1].samples[0].s22_MPa,
              30.0 / (1.0 - 0.45 * 0.45) * e + 0.45 / 0.55 * (-Br * height), 1e-12);
}

// A cycle of samples every `step` mm along a 1000 mm path, F and K from functions of s.
template <class Force, class Curvature>
belt::LoadCycle path_cycle(double step, Force F, Curvature K) {
  belt::LoadCycle c;
  c.cycle_length_mm = 1000.0;
  for (double s = 0.0; s < 1000.0 - 1e-9; s += step) {
    belt::LoadSample x;
    x.s_mm = s, x.F_N = F(s), x.K_1_mm = K(s);
    c.samples.push_back(x);
  }
  return c;
}

TEST(BeamSection, ABendThatChangesAlongThePathShearsTheCushionAsJourawskisBeam) {
  // K rises linearly from 0 to 1/40 mm⁻¹ over s = 300…400 (a sheave's entrance), F = 800 N, no
  // pressure. In the ramp, farther than half a pitch from its ends, the pitch-mean of ∂ε22/∂s is
  // −(1 + ε) K′ d exactly (K_m = 0), so σ12 = ∫ from the point to the free bottom of
  // E/(1 − ν²) (−(1 + ε) K′ d) w dd, w = 1 in the land and the cog fill in the cogs.
  const double K1 = 1.0 / 40.0, slope = K1 / 100.0, eps = 800.0 / 40000.0;
  auto K = [&](double s) { return s < 300.0 ? 0.0 : s > 400.0 ? K1 : slope * (s - 300.0); };
  const auto h = beam_stress_histories(path_cycle(0.5, [](double) { return 800.0; }, K), drive(), section());
  const double nu2 = 1.0 - 0.45 * 0.45, c = 0.5, d = 0.25, land = 4.1, cogs = 2.5, fill = 0.51;
  auto moment = [](double a, double b) { return 0.5 * (b * b - a * a); };  // ∫ d dd
  const double tau = -(1.0 + eps) * slope *
                     (30.0 / nu2 * moment(d, c) + 12.0 / nu2 * (moment(c, land) + fill * moment(land, land + cogs)));
  const std::size_t in_ramp = 700;  // s = 350 mm
  ASSERT_DOUBLE_EQ(h[1].samples[in_ramp].t_s, 350.0 / 10000.0);
  EXPECT_NEAR(h[1].samples[in_ramp].s12_MPa, tau, 1e-12 * std::abs(tau));
  // The gap bottom is the free surface: no shear; a straight span and the uniform wrap: none.
  EXPECT_EQ(h[0].samples[in_ramp].s12_MPa, 0.0);
  EXPECT_EQ(h[1].samples[400].s12_MPa, 0.0);  // s = 200
  EXPECT_NEAR(h[1].samples[1000].s12_MPa, 0.0, 1e-15);  // s = 500
  // pitch 0: the point beam of §5a, which carries no bending shear.
  BeamSection point = section();
  point.pitch_mm = 0.0;
  const auto p = beam_stress_histories(path_cycle(0.5, [](double) { return 800.0; }, K), drive(), point);
  EXPECT_EQ(p[1].samples[in_ramp].s12_MPa, 0.0);
}

TEST(BeamSection, BodyForcesAreTheirMeanOverOneCogPitch) {
  // A pressure spike narrower than the pitch: triangle of height p0 and half-width a = 2 mm at
  // s = 0 (it wraps round the path's end), μ_used = 0.5 at γ = 90° (B_l = −μ q cos β_s, β_s = 0).
  // At the spike the cushion carries the pitch's mean, p0 a/pitch, not the peak; a pitch away none.
  const double p0 = 3.0, a = 2.0, pitch = 9.0, B = 11.0, beta = 0.3, height = 4.1 - 0.25 + 0.51 * 2.5;
  belt::LoadCycle c = path_cycle(0.5, [](double) { return 0.0; }, [](double) { return 0.0; });
  for (belt::LoadSample& x : c.samples) {
    const double r = std::min(x.s_mm, 1000.0 - x.s_mm);
    x.p_MPa = std::max(0.0, p0 * (1.0 - r / a));
    x.gamma_rad = 1.5707963267948966, x.friction_used = 0.5;
  }
  const auto h = beam_stress_histories(c, drive(), section());
  const double Bl_peak = -0.5 * p0 * (2.0 / B) / std::cos(beta);
  EXPECT_NEAR(h[1].samples[0].s12_MPa, Bl_peak * a / pitch * height, 1e-12);
  EXPECT_NEAR(h[1].samples[1999].s12_MPa, h[1].samples[1].s12_MPa, 1e-12);  // s = 999.5 and 0.5
  EXPECT_EQ(h[1].samples[20].s12_MPa, 0.0);  // s = 10 mm: the spike is out of its pitch
  BeamSection point = section();
  point.pitch_mm = 0.0;
  EXPECT_NEAR(beam_stress_histories(c, drive(), point)[1].samples[0].s12_MPa, Bl_peak * height, 1e-12);
  point.pitch_mm = -1.0;
  EXPECT_THROW(beam_stress_histories(c, drive(), point), core::InputError);
}

TEST(BeamSection, DefaultsFollowTheDrivesBendingStiffnessAndLength) {
  belt::DriveCase d = drive();
  d.belt.EI_Nmm2 = 834.0 * 12.5;
  d.geometry.belt_length_mm = 1000.0;
  const BeamSection s = default_beam_section(d, 80.0);
  EXPECT_DOUBLE_EQ(s.bottom_modulus_MPa, 12.5);
  EXPECT_DOUBLE_EQ(s.cushion_modulus_MPa, 12.5);
  EXPECT_DOUBLE_EQ(s.manufactured_curvature_1_mm, 2.0 * 3.14159265358979323846 / 1000.0);
  d.belt.EI_Nmm2 = 0.0;  // none: the Fritzson law E0 (1 + (20 − T)·0.001786) with E0 = 10 MPa
  EXPECT_NEAR(default_beam_section(d, 80.0).bottom_modulus_MPa, 10.0 * (1.0 - 60.0 * 0.001786), 1e-12);
}

TEST(BeamSection, RefusesAStandingBeltAndBadSections) {
  belt::DriveCase d = drive();
  d.belt_speed_mm_s = 0.0;
  try {
    beam_stress_histories(one_sample(1.0, 0.0), d, section());
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("running belt"), std::string::npos);
  }
  EXPECT_THROW(cycle_conditions(one_sample(1.0, 0.0), d, 80.0), core::InputError);
  BeamSection s = section();
  s.cushion_depths_mm = {0.7};
  EXPECT_THROW(beam_stress_histories(one_sample(1.0, 0.0), drive(), s), core::InputError);
  s = section();
  s.poisson = 0.5;
  EXPECT_THROW(beam_stress_histories(one_sample(1.0, 0.0), drive(), s), core::InputError);
}

TEST(BeamSection, LifeOfASyntheticCycleMatchesTheHandSum) {
  // Span (straight, tension) → pulley (bent) → span: at the gap bottom σ22 = E'ε22 goes
  // + → − → +; σ_e is σ22 in tension and |τ| at ±25° in compression. The cushion sees no
  // pressure and, in the point beam (pitch 0), no shear from the bend's steps, so separation is
  // unbounded.
  belt::LoadCycle c;
  const double F = 400.0;
  for (int i = 0; i < 30; ++i) {
    belt::LoadSample s;
    s.s_mm = 10.0 * i;
    s.F_N = F;
    s.K_1_mm = (i >= 10 && i < 20) ? 0.02 : 0.0;
    c.samples.push_back(s);
  }
  c.cycle_length_mm = 300.0;
  BeamSection s = section();
  s.pitch_mm = 0.0;
  const FatigueCard card = default_card();
  const LifeReport r = beam_life(c, drive(), s, card, card.reference_temperature_C);
  const double Eg = 12.0 / (1.0 - 0.45 * 0.45);
  const double tension = Eg * 0.01;
  const double bent = Eg * std::abs(1.01 * (1.0 - 0.02 * 4.1) - 1.0);
  const double shear = bent * std::sin(25.0 * 3.14159265358979323846 / 180.0) *
                       std::cos(25.0 * 3.14159265358979323846 / 180.0);
  ASSERT_EQ(r.modes.size(), 2u);
  // σ_e has two plateaus per cycle and nothing between them (no sample at the sign change):
  // the larger is the one maximum, the smaller the one minimum.
  const double larger = std::max(tension, shear);
  ASSERT_EQ(r.modes[0].peaks.size(), 1u);
  EXPECT_NEAR(r.modes[0].peaks[0].stress_MPa, larger, 1e-12);
  EXPECT_NEAR(r.modes[0].life_cycles, std::pow(104.218 / larger, 4.423), 1e-6 * r.modes[0].life_cycles);
  EXPECT_FALSE(std::isfinite(r.modes[1].life_cycles));
  EXPECT_EQ(r.governing, "radial_crack");
  EXPECT_NEAR(r.life_h, r.life_cycles / (3600.0 * 10000.0 / 300.0), 1e-9 * r.life_h);
}

}  // namespace
}  // namespace fitlib::fatigue
