// [life] uncertainty = "cards" (docs/thermal.md §7): the bottom card's parameter covariance
// propagated to B10/B50 by seeded draws on the sweep engine's threads. Same seed, same bytes (for
// any thread count); a larger covariance gives a wider interval; B10 < B50; the deterministic life
// stays the median.
#include <gtest/gtest.h>

#include <cmath>

#include "common/temp_path.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/scene/writers.hpp"

using namespace fitlib;

namespace {

const std::string kSource = FITLIB_SOURCE_DIR;

// The thesis bottom card with a covariance of its mean moduli in ln coordinates: variance v, the
// three correlated by 0.5.
std::string bottom_card(double v, const std::string& name) {
  card::Card c = card::load_card(kSource + "/datasets/cards/material-1-true.json");
  const double r = 0.5 * v;
  c.fit["covariance"] = {{"parameters", {"G_Im", "C33_Am", "C44_Am"}},
                         {"coordinates", {"ln", "ln", "ln"}},
                         {"matrix", {{v, r, r}, {r, v, r}, {r, r, v}}}};
  const std::string path = fitlib_test::temp_path(name);
  card::save_card(path, c);
  return path;
}

std::string fatigue_card() {
  fatigue::FatigueCard c = fatigue::default_card();
  c.radial_crack.scatter = fatigue::LifeScatter{"lognormal", 0.3, 12};
  c.separation.scatter = fatigue::LifeScatter{"lognormal", 0.25, 10};
  c.separation.covariance = fatigue::LawCovariance{{{1e-3, 0.0, 0.0}, {0.0, 0.04, 0.0}, {0.0, 0.0, 1e-5}}};
  const std::string path = fitlib_test::temp_path("uncertainty-fatigue.json");
  fatigue::save_card(path, c);
  return path;
}

scene::Scene drive(const std::string& bottom, int samples = 48, std::uint64_t seed = 7) {
  auto s = scene::load_scene(kSource + "/datasets/drives/ref-0500-medium.toml");
  s.materials["bottom"] = bottom;
  s.life = scene::LifeSpec{};
  s.life->fidelity = core::Fidelity::beam;
  s.life->card = fatigue_card();
  s.life->uncertainty_cards = true;
  s.life->samples = samples;
  s.life->seed = seed;
  return s;
}

double log_width(const fatigue::BLife& b) { return std::log10(b.cards_high_cycles / b.cards_low_cycles); }

TEST(CardUncertainty, SameSeedGivesIdenticalBytesForAnyThreadCount) {
  auto s = drive(bottom_card(4e-3, "seed.json"));
  auto one = s;
  one.segment_thread_cap = 1;
  const auto a = scene::run_life(s), b = scene::run_life(one);
  const std::string ja = scene::life_json(s, a, false).dump(2);
  EXPECT_EQ(ja, scene::life_json(one, b, false).dump(2));
  EXPECT_EQ(scene::life_text(s, a), scene::life_text(one, b));
  EXPECT_NE(ja.find("ci90_cards_h"), std::string::npos) << ja;
  auto other = s;
  other.life->seed = 8;
  const auto c = scene::run_life(other);
  EXPECT_NE(c.life->distribution[0].b10.cards_low_cycles, a.life->distribution[0].b10.cards_low_cycles);
  EXPECT_EQ(c.life->distribution[0].b50.cycles, a.life->distribution[0].b50.cycles);  // the median is not drawn
}

TEST(CardUncertainty, IntervalWidensWithTheCardCovarianceAndKeepsTheDeterministicMedian) {
  const auto small = scene::run_life(drive(bottom_card(1e-3, "small.json")));
  const auto large = scene::run_life(drive(bottom_card(4e-3, "large.json")));
  ASSERT_EQ(small.life->distribution.size(), 2u);
  for (std::size_t m = 0; m < 2; ++m) {
    const auto& a = small.life->distribution[m];
    const auto& b = large.life->distribution[m];
    ASSERT_TRUE(a.cards && b.cards);
    EXPECT_EQ(a.cards->failed, 0);
    EXPECT_EQ(b.b50.cycles, small.life->report.modes[m].life_cycles);  // B50 is the deterministic life
    for (const auto* d : {&a, &b}) {
      EXPECT_LT(d->b10.cycles, d->b50.cycles);
      EXPECT_LT(d->b10.cards_high_cycles, d->b50.cards_low_cycles * 10.0);
      EXPECT_LT(d->b50.cards_low_cycles, d->b50.cycles);
      EXPECT_GT(d->b50.cards_high_cycles, d->b50.cycles);
      // the draws' median is the deterministic life, to the draws' sampling error (linear response: exact)
      EXPECT_NEAR(std::log10(d->cards->median_cycles / d->b50.cycles), 0.0, 0.25 * log_width(d->b50));
    }
    EXPECT_GT(log_width(a.b50), 0.0);
    // Four times the variance: twice the standard deviation, so about twice the interval in log life.
    EXPECT_NEAR(log_width(b.b50) / log_width(a.b50), 2.0, 0.3) << m;
    EXPECT_NEAR(log_width(b.b10) / log_width(b.b50), 1.0, 1e-12);  // B10 = B50 10^(z s): the same spread
  }
}

TEST(CardUncertainty, ACardWithoutCovarianceOrStandardErrorsIsRefused) {
  auto s = drive(kSource + "/datasets/cards/material-1-true.json");
  try {
    scene::run_life(s);
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), "life.uncertainty") << e.what();
  }
  const std::string base = fitlib::core::read_file(kSource + "/datasets/drives/ref-0500-medium.toml");
  const auto parsed = scene::parse_scene(base + "\n[life]\nuncertainty = \"cards\"\nsamples = 10\nseed = 3\n", "x.toml");
  EXPECT_TRUE(parsed.life->uncertainty_cards);
  EXPECT_EQ(parsed.life->samples, 10);
  EXPECT_EQ(parsed.life->seed, 3u);
  EXPECT_THROW(scene::parse_scene(base + "\n[life]\nuncertainty = \"card\"\n", "x.toml"), core::InputError);
  EXPECT_THROW(scene::parse_scene(base + "\n[life]\nsamples = 1\n", "x.toml"), core::InputError);
}

// [life] uncertainty = "constants+cards": the same draws make a third interval, both sources as one
// distribution, wider than either alone; the cards' interval is the "cards" run's; same bytes for any
// thread count. The radial crack's law has no covariance: its combined interval is the cards'.
TEST(CardUncertainty, ConstantsPlusCardsIsOneWiderIntervalAndByteReproducible) {
  auto s = drive(bottom_card(4e-3, "combined.json"));
  auto cards_only = s;
  s.life->uncertainty_combined = true;
  auto one = s;
  one.segment_thread_cap = 1;
  const auto a = scene::run_life(s), b = scene::run_life(one), c = scene::run_life(cards_only);
  const std::string ja = scene::life_json(s, a, false).dump(2);
  EXPECT_EQ(ja, scene::life_json(one, b, false).dump(2));
  EXPECT_NE(ja.find("ci90_combined_h"), std::string::npos) << ja;
  EXPECT_NE(scene::life_text(s, a).find(" combined ["), std::string::npos);
  ASSERT_EQ(a.life->distribution.size(), 2u);
  const auto& crack = a.life->distribution[0];
  EXPECT_EQ(crack.b10.combined_low_cycles, crack.b10.cards_low_cycles);
  const auto& sep = a.life->distribution[1];
  EXPECT_EQ(sep.b50.cards_low_cycles, c.life->distribution[1].b50.cards_low_cycles);
  EXPECT_FALSE(c.life->distribution[1].b50.has_combined_interval);
  for (const fatigue::BLife* x : {&sep.b10, &sep.b50}) {
    const double combined = std::log10(x->combined_high_cycles / x->combined_low_cycles);
    EXPECT_GT(combined, log_width(*x));
    EXPECT_GT(combined, std::log10(x->high_cycles / x->low_cycles));
    EXPECT_LT(x->combined_low_cycles, x->cycles);
    EXPECT_GT(x->combined_high_cycles, x->cycles);
  }
  const std::string base = fitlib::core::read_file(kSource + "/datasets/drives/ref-0500-medium.toml");
  const auto parsed = scene::parse_scene(base + "\n[life]\nuncertainty = \"constants+cards\"\n", "x.toml");
  EXPECT_TRUE(parsed.life->uncertainty_cards && parsed.life->uncertainty_combined);
}

}  // namespace
