// Fritzson's model: cost of the complex (steady sinusoidal) form against time integration to the
// steady state (thesis L2222: the complex form is 100–1000× faster), and the integrator's
// accuracy versus time (steps per cycle → error against the complex form, wall time).
// Plain main; prints its tables. Material: the true material-1 card (datasets/cards).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/model/fritzson.hpp"
#include "fitlib/model/fritzson_point.hpp"
#include "fitlib/model/material_point.hpp"

using namespace fitlib::model;
using namespace fitlib::model::fritzson;
using Clock = std::chrono::steady_clock;

namespace {

template <typename F>
double seconds_per_call(F&& f, double min_seconds = 0.2) {
  long calls = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  do {
    f();
    ++calls;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < min_seconds);
  return elapsed / calls;
}

TestCondition condition(TestMode mode, const char* o, double amplitude, double mean) {
  TestCondition c;
  c.mode = mode;
  c.orientation = o;
  c.frequency_Hz = 10.0;
  c.temperature_C = 60.0;
  c.strain_amplitude = amplitude;
  c.mean_strain = mean;
  return c;
}

}  // namespace

int main() {
  const auto card = fitlib::card::load_card(std::string(FITLIB_SOURCE_DIR) +
                                            "/datasets/cards/material-1-true.json");
  const auto model = card.model();
  const std::vector<double> p = card.values();
  const std::vector<TestCondition> tests = {condition(TestMode::shear, "12", 0.02, 0.02),
                                            condition(TestMode::shear, "23", 0.02, 0.02),
                                            condition(TestMode::uniaxial, "22", 0.01, -0.01),
                                            condition(TestMode::uniaxial, "33", 0.005, -0.005)};
  volatile double sink = 0.0;

  std::printf("Speed: complex form vs time integration to a steady state (material 1, 10 Hz, 60 C)\n");
  std::printf("%-12s %12s %12s %16s %12s %16s %10s\n", "test", "complex_us", "jacobian_us",
              "10cyc x 64 ms", "ratio", "200cyc x 128 ms", "ratio");
  for (const TestCondition& c : tests) {
    const double t_complex = seconds_per_call([&] { sink = sink + model->moduli(p.data(), c).storage; });
    Eigen::MatrixXd J(3, model->size());
    const double t_jac = seconds_per_call([&] { sink = sink + model->moduli(p.data(), c, J).storage; });
    const fritzson::MaterialPoint point(p, true, 23.0, Scheme::exponential);
    auto integrate = [&](int cycles, int steps) {
      const StrainHistory h = cyclic_history(c.strain_amplitude, c.mean_strain, c.frequency_Hz,
                                             cycles, steps);
      const fritzson::DriveResult r = drive_test(point, c, h);
      sink = sink + cycle_moduli(h.time_s, h.strain, r.stress, c.frequency_Hz).storage;
    };
    const double t_short = seconds_per_call([&] { integrate(10, 64); });
    const double t_long = seconds_per_call([&] { integrate(200, 128); });
    std::printf("%-12s %12.3f %12.3f %16.3f %12.0f %16.2f %10.0f\n",
                (std::string(to_string(c.mode)) + " " + c.orientation).c_str(), t_complex * 1e6,
                t_jac * 1e6, t_short * 1e3, t_short / t_complex, t_long * 1e3, t_long / t_complex);
  }

  std::printf("\nAccuracy vs time: 50 cycles; error of the last cycle's moduli against the same\n"
              "integration with 4096 steps per cycle (discretisation error), and the deviation of\n"
              "that reference from the complex form (physics floor: damage still settling with\n"
              "C_d = 0.6 and the running mean's 1/t tail)\n");
  std::printf("%-12s %-15s %8s %12s %12s %12s %10s\n", "test", "scheme", "steps", "storage",
              "loss", "mean", "wall_ms");
  for (const TestCondition& c : {tests[0], tests[2]}) {
    const std::string label = std::string(to_string(c.mode)) + " " + c.orientation;
    const Moduli<double> exact = model->moduli(p.data(), c);
    for (Scheme scheme : {Scheme::backward_euler, Scheme::exponential}) {
      const fritzson::MaterialPoint point(p, true, 23.0, scheme);
      auto run = [&](int steps, double* wall_ms) {
        const StrainHistory h = cyclic_history(c.strain_amplitude, c.mean_strain, c.frequency_Hz,
                                               50, steps);
        const auto start = Clock::now();
        const fritzson::DriveResult r = drive_test(point, c, h);
        if (wall_ms) *wall_ms = std::chrono::duration<double>(Clock::now() - start).count() * 1e3;
        return cycle_moduli(h.time_s, h.strain, r.stress, c.frequency_Hz);
      };
      const Moduli<double> reference = run(4096, nullptr);
      const char* name = scheme == Scheme::exponential ? "exponential" : "backward-euler";
      std::printf("%-12s %-15s %8s %12.2e %12.2e %12.2e %10s\n", label.c_str(), name, "floor",
                  std::abs(reference.storage / exact.storage - 1),
                  std::abs(reference.loss / exact.loss - 1),
                  std::abs(reference.mean / exact.mean - 1), "-");
      for (int steps : {8, 16, 32, 64, 128, 256, 512}) {
        double wall = 0.0;
        const Moduli<double> m = run(steps, &wall);
        std::printf("%-12s %-15s %8d %12.2e %12.2e %12.2e %10.2f\n", label.c_str(), name, steps,
                    std::abs(m.storage / reference.storage - 1),
                    std::abs(m.loss / reference.loss - 1), std::abs(m.mean / reference.mean - 1),
                    wall);
      }
    }
  }

  std::printf("\nMaterial-point update (one call, 3-D, material 1): ");
  const fritzson::MaterialPoint point(p, true, 23.0, Scheme::backward_euler);
  MaterialState state, next;
  Vector6 strain;
  strain << -0.01, 0.005, 0.004, 0.002, 0.003, 0.01;
  Matrix6 tangent;
  const double t_plain = seconds_per_call([&] { sink = sink + point.update(state, strain, 1e-3, 60, next)[0]; });
  const double t_tan = seconds_per_call([&] { sink = sink + point.update(state, strain, 1e-3, 60, next, &tangent)[0]; });
  std::printf("stress only %.3f us, with consistent tangent %.3f us (ratio %.1f)\n", t_plain * 1e6,
              t_tan * 1e6, t_tan / t_plain);

  // The same update through the material-point contract (flat state, virtual call): the best of
  // five interleaved rounds each, so a busy machine affects both alike.
  const auto contract = fitlib::model::make_material_point(*make_model("fritzson", {}), p);
  std::vector<double> flat = contract->initial_state(), flat_next(contract->state_size());
  double best[4] = {1e9, 1e9, 1e9, 1e9};
  for (int round = 0; round < 5; ++round) {
    best[0] = std::min(best[0], seconds_per_call([&] { sink = sink + point.update(state, strain, 1e-3, 60, next)[0]; }));
    best[1] = std::min(best[1], seconds_per_call([&] { sink = sink + contract->update(flat.data(), strain, 1e-3, 60, flat_next.data())[0]; }));
    best[2] = std::min(best[2], seconds_per_call([&] { sink = sink + point.update(state, strain, 1e-3, 60, next, &tangent)[0]; }));
    best[3] = std::min(best[3], seconds_per_call([&] { sink = sink + contract->update(flat.data(), strain, 1e-3, 60, flat_next.data(), &tangent)[0]; }));
  }
  std::printf("Through the contract: stress only %.3f us vs %.3f us direct (%+.1f %%), with tangent "
              "%.3f us vs %.3f us (%+.1f %%)\n", best[1] * 1e6, best[0] * 1e6,
              100.0 * (best[1] / best[0] - 1.0), best[3] * 1e6, best[2] * 1e6,
              100.0 * (best[3] / best[2] - 1.0));
  return sink == 12345.678 ? 1 : 0;
}
