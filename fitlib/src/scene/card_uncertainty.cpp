// [life] uncertainty = "cards" or "constants+cards" (docs/thermal.md §7): the material cards'
// parameter covariance propagated to B10 and B50 by running the scene's life on seeded draws of the
// cards, on the sweep engine's schedule (an IndexedExecutor: this process's threads, or the MPI
// ranks under mpirun), each draw's life stored at its index as an exact text; with
// "constants+cards" the draws also make the combined interval.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include "effects.hpp"
#include "fitlib/card/covariance.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/sweep.hpp"
#include "fitlib/scene/sweep_run.hpp"

namespace fitlib::scene::detail {
namespace {

struct RoleSampler {
  std::string role;
  card::CardSampler sampler;
  std::uint64_t stream;  // the role's own random stream: bottom 1, cushion 2, cord 3
};

std::vector<RoleSampler> role_samplers(const Scene& s, std::vector<std::string>& warnings) {
  std::vector<RoleSampler> out;
  std::uint64_t stream = 0;
  for (const char* role : kCardRoles) {
    ++stream;
    if (!s.materials.count(role)) continue;
    const std::string& path = s.materials.at(role);
    const card::Card c = material_card(s, role);
    auto cov = card::card_covariance(c, path);
    if (!cov) continue;
    if (!cov->correlated)
      warnings.push_back("card " + path + " (" + role + ") has no fit.covariance: [life] uncertainty = \"cards\" draws "
                         "its standard errors as independent (their correlations are unknown)");
    try {
      out.push_back({role, card::CardSampler(c, std::move(*cov)), stream});
    } catch (const core::InputError& e) {
      throw core::InputError(e.detail().empty() ? e.what() : e.detail(), path, 0, 0, "fit.covariance");
    }
  }
  if (out.empty())
    throw core::InputError("[life] uncertainty = \"cards\" propagates the material cards' parameter covariance, and "
                           "no card of the scene's [belt.materials] has one (fit.covariance) or standard errors "
                           "(cards fitted by fitcli fit carry both)",
                           s.path, 0, 0, "life.uncertainty");
  return out;
}

// The draws' cost against the sweep's work cap (the same per-case costs, docs/decisions.md
// "sweep: work cap in core-hours").
void check_draws_cost(const Scene& s, core::Fidelity fidelity) {
  const double each = fidelity == core::Fidelity::beam      ? kSweepCaseCostS.beam
                      : fidelity == core::Fidelity::elastic ? kSweepCaseCostS.elastic
                                                            : kSweepCaseCostS.complete;
  const double core_hours = each * s.life->samples / 3600.0;
  if (core_hours <= kMaxSweepCoreHours) return;
  throw core::InputError("[life] samples = " + std::to_string(s.life->samples) + " draws at fidelity " + core::to_string(fidelity) +
                             " take about " + std::to_string(static_cast<int>(core_hours)) +
                             " core-hours, beyond the work cap of 24: fewer samples or a cheaper fidelity",
                         s.path, 0, 0, "life.samples");
}

// Draw k's scene: the cards' values drawn, the life alone, one segment thread (the draws run in
// parallel themselves).
Scene draw_scene(const Scene& s, const std::vector<RoleSampler>& samplers, std::size_t k) {
  Scene d = s;
  d.life->uncertainty_cards = d.life->uncertainty_combined = false;
  d.outputs = {{"life", true}};
  d.life_field_at.clear();
  d.segment_progress = false;
  d.segment_thread_cap = 1;
  d.draw_executor = nullptr;
  for (const RoleSampler& r : samplers) d.card_values[r.role] = r.sampler.draw(s.life->seed, r.stream, k);
  return d;
}

// A draw's outcome as a text (what crosses between MPI ranks): "!" and the reason it stopped, or
// per mode "<mode> <16 hex digits of the life's bits>;" — exact, so every executor gives the same
// lives to the bit.
std::string draw_text(const std::map<fatigue::Mode, double>& lives) {
  std::string out;
  for (const auto& [mode, cycles] : lives) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &cycles, sizeof bits);
    char buf[40];
    std::snprintf(buf, sizeof buf, "%d %016llx;", static_cast<int>(mode), static_cast<unsigned long long>(bits));
    out += buf;
  }
  return out;
}

std::map<fatigue::Mode, double> draw_lives(const std::string& text) {
  std::map<fatigue::Mode, double> lives;
  for (std::size_t at = 0; at < text.size();) {
    int mode = 0;
    unsigned long long bits = 0;
    int used = 0;
    if (std::sscanf(text.c_str() + at, "%d %16llx;%n", &mode, &bits, &used) != 2 || used == 0)
      throw std::logic_error("card draws: unreadable draw text '" + text + "'");
    double cycles = 0.0;
    const std::uint64_t b = bits;
    std::memcpy(&cycles, &b, sizeof cycles);
    lives[static_cast<fatigue::Mode>(mode)] = cycles;
    at += static_cast<std::size_t>(used);
  }
  return lives;
}

// The draws' texts (draw_text) on the scene's executor: draw k runs the scene's life on draw k of
// the cards. A draw whose run stops (a runaway, a drawn card without a material at T) is counted,
// not fatal.
std::vector<std::string> draw_texts(const Scene& s, const std::vector<RoleSampler>& samplers, std::size_t n) {
  auto draw = [&](std::size_t k) -> std::string {
    try {
      const SceneResult drawn = run_life(draw_scene(s, samplers, k));  // held: the loop reads into it
      std::map<fatigue::Mode, double> lives;
      for (const fatigue::ModeLife& m : drawn.life->report.modes) lives[m.mode] = m.life_cycles;
      return draw_text(lives);
    } catch (const core::InputError& e) {
      return std::string("!") + e.what();
    } catch (const core::NumericalError& e) {
      return std::string("!") + e.what();
    }
  };
  ThreadIndexedExecutor threads;
  IndexedExecutor& executor = s.draw_executor ? *s.draw_executor : threads;
  return executor.texts(n, segment_threads(s), draw);
}

// The scene's draws (their samplers) when [life] uncertainty asks for them, checked as
// card_uncertainty checks them (InputError: no card with a covariance, beyond the work cap).
std::optional<std::vector<RoleSampler>> due_samplers(const Scene& s, core::Fidelity fidelity,
                                                     std::vector<std::string>& warnings) {
  if (!s.life || !s.life->uncertainty_cards) return std::nullopt;
  std::vector<RoleSampler> samplers = role_samplers(s, warnings);
  check_draws_cost(s, fidelity);
  return samplers;
}

// Whether the writer's card_uncertainty runs draws, from the scene alone, so that every process
// sharing them decides alike: their samplers, or nullopt. The fidelity is the plan's with the life
// asked for, as run_life asks for it.
std::optional<std::vector<RoleSampler>> due_samplers(const Scene& s) {
  Scene life = s;
  life.outputs["life"] = true;
  std::vector<std::string> warnings;
  return due_samplers(s, make_plan(life).life->fidelity, warnings);
}

// The writer's executor, remembering whether the writer's life joined the draws.
class JoinedOnce : public IndexedExecutor {
 public:
  explicit JoinedOnce(std::shared_ptr<IndexedExecutor> shared) : shared_(std::move(shared)) {}
  std::vector<std::string> texts(std::size_t n, int threads, const std::function<std::string(std::size_t)>& work) override {
    joined_ = true;
    return shared_->texts(n, threads, work);
  }
  // The writer's life did not reach its draws (it stopped before them, or its fatigue card gives
  // no distribution): join the other processes' gather with empty draws of its own, so that none
  // waits for it; nothing here may throw over the writer's own outcome.
  void join_if_due(const Scene& s) noexcept {
    if (joined_) return;
    joined_ = true;
    try {
      if (const auto samplers = due_samplers(s))
        shared_->texts(static_cast<std::size_t>(s.life->samples), 1, [](std::size_t) { return std::string("!"); });
    } catch (...) {  // the others refused the same draws, or one failed: they are not waiting
    }
  }

 private:
  std::shared_ptr<IndexedExecutor> shared_;
  bool joined_ = false;
};

}  // namespace

void card_uncertainty(const Scene& s, SceneResult& r, LifeResult& life) {
  if (life.distribution.empty()) return;
  const auto samplers = due_samplers(s, life.plan.fidelity, r.warnings);
  if (!samplers) return;
  const auto n = static_cast<std::size_t>(s.life->samples);
  const std::vector<std::string> texts = draw_texts(s, *samplers, n);
  std::vector<std::map<fatigue::Mode, double>> lives(n);
  std::vector<std::string> failures(n);
  for (std::size_t k = 0; k < n; ++k)
    if (!texts[k].empty() && texts[k][0] == '!') failures[k] = texts[k].size() > 1 ? texts[k].substr(1) : "stopped";
    else lives[k] = draw_lives(texts[k]);
  fatigue::CardsSampling sampling;
  sampling.samples = s.life->samples;
  sampling.seed = s.life->seed;
  for (const std::string& f : failures)
    if (!f.empty() && sampling.failed++ == 0) sampling.first_failure = f;
  for (fatigue::ModeDistribution& d : life.distribution) {
    std::vector<double> cycles;
    for (const auto& draw : lives)
      if (const auto m = draw.find(d.mode); m != draw.end()) cycles.push_back(m->second);
    fatigue::add_cards_interval(d, cycles, sampling);
    if (s.life->uncertainty_combined) fatigue::add_combined_interval(d, cycles);
  }
}

}  // namespace fitlib::scene::detail

namespace fitlib::scene {

std::optional<SceneResult> run_life_sharing_draws(const Scene& s, bool writes) {
  if (!s.draw_executor) return run_life(s);
  if (!writes) {  // only this process's share of the draws: the writer alone needs the deterministic life
    if (const auto samplers = detail::due_samplers(s))
      detail::draw_texts(s, *samplers, static_cast<std::size_t>(s.life->samples));
    return std::nullopt;
  }
  Scene writer = s;
  const auto once = std::make_shared<detail::JoinedOnce>(s.draw_executor);
  writer.draw_executor = once;
  try {
    SceneResult r = run_life(writer);
    once->join_if_due(s);
    return r;
  } catch (...) {
    once->join_if_due(s);
    throw;
  }
}

}  // namespace fitlib::scene
