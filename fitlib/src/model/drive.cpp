// One driver for every material point (docs/model.md §"drive"): strain- or stress-controlled
// Voigt components over time, stress-controlled ones solved by Newton with the point's tangent.
#include <Eigen/Dense>
#include <cmath>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/material_point.hpp"

namespace fitlib::model {
namespace {

double value_at(const DriveControl& c, size_t n) { return c.values.empty() ? 0.0 : c.values[n]; }

void check_program(const DriveProgram& p) {
  const size_t n = p.time_s.size();
  if (n == 0) throw core::UsageError("drive: the program has no times");
  for (size_t k = 1; k < n; ++k)
    if (!(p.time_s[k] > p.time_s[k - 1]))
      throw core::UsageError("drive: times must increase strictly (sample " + std::to_string(k) + ")");
  for (int i = 0; i < 6; ++i)
    if (!p.components[i].values.empty() && p.components[i].values.size() != n)
      throw core::UsageError("drive: component " + std::to_string(i + 1) + " has " +
                             std::to_string(p.components[i].values.size()) + " values for " +
                             std::to_string(n) + " times");
  if (!p.temperature_C.empty() && p.temperature_C.size() != n)
    throw core::UsageError("drive: temperature needs one value per time");
  // A non-finite input would come out as a non-finite stress, or as a stress control that "did
  // not converge": say which sample it is instead.
  for (size_t k = 0; k < n; ++k) {
    if (!std::isfinite(p.time_s[k])) throw core::UsageError("drive: time " + std::to_string(k) + " is not finite");
    for (int i = 0; i < 6; ++i)
      if (!p.components[i].values.empty() && !std::isfinite(p.components[i].values[k]))
        throw core::UsageError("drive: component " + std::to_string(i + 1) + " is not finite at sample " +
                               std::to_string(k));
    if (!p.temperature_C.empty() && std::isinf(p.temperature_C[k]))
      throw core::UsageError("drive: temperature " + std::to_string(k) + " is infinite (NaN = the reference)");
  }
}

// Voigt index of a test's imposed component from its orientation label ("12", "22", ...);
// isotropic default: shear 12, uniaxial 22.
int test_component(const TestCondition& c) {
  const std::string& o = c.orientation;
  int i = c.mode == TestMode::uniaxial ? 1 : 0, j = 1;
  if (!o.empty()) {
    if (o.size() != 2 || o[0] < '1' || o[0] > '3' || o[1] < '1' || o[1] > '3')
      throw core::UsageError("orientation '" + o + "' is not 11, 22, 33, 12, 13 or 23");
    i = o[0] - '1';
    j = o[1] - '1';
  }
  if (c.mode == TestMode::uniaxial) {
    if (i != j) throw core::UsageError("uniaxial orientation must be 11, 22 or 33");
    return i;
  }
  if (i == j) throw core::UsageError("shear orientation must be 12, 13 or 23");
  return (i + j == 3) ? 3 : (i + j == 2) ? 4 : 5;  // 23, 13, 12
}

}  // namespace

DriveResult drive(const MaterialPoint& point, const DriveProgram& program) {
  check_program(program);
  std::vector<int> free;
  for (int i = 0; i < 6; ++i)
    if (program.components[i].imposed == DriveControl::Imposed::stress) free.push_back(i);
  const int nf = static_cast<int>(free.size());

  DriveResult out;
  std::vector<double> state = point.initial_state(), next(point.state_size());
  Vector6 strain = Vector6::Zero(), stress;
  Matrix6 C;
  for (size_t n = 0; n < program.time_s.size(); ++n) {
    const double dt = n == 0 ? 0.0 : program.time_s[n] - program.time_s[n - 1];
    const double T = program.temperature_C.empty() ? std::nan("") : program.temperature_C[n];
    for (int i = 0; i < 6; ++i)
      if (program.components[i].imposed == DriveControl::Imposed::strain)
        strain[i] = value_at(program.components[i], n);
    bool converged = nf == 0;
    stress = point.update(state.data(), strain, dt, T, next.data(), nf ? &C : nullptr);
    for (int iteration = 0; nf && iteration < program.max_iterations; ++iteration) {
      Eigen::VectorXd residual(nf);
      Eigen::MatrixXd J(nf, nf);
      for (int a = 0; a < nf; ++a) {
        residual[a] = stress[free[a]] - value_at(program.components[free[a]], n);
        for (int b = 0; b < nf; ++b) J(a, b) = C(free[a], free[b]);
      }
      if (residual.cwiseAbs().maxCoeff() <= program.stress_tolerance_MPa * (1.0 + stress.cwiseAbs().maxCoeff())) {
        converged = true;
        break;
      }
      const Eigen::VectorXd step = J.partialPivLu().solve(-residual);
      if (!step.allFinite()) break;
      for (int a = 0; a < nf; ++a) strain[free[a]] += step[a];
      stress = point.update(state.data(), strain, dt, T, next.data(), &C);
    }
    if (!converged)
      throw core::NumericalError("drive: stress-controlled components did not converge at t = " +
                                 core::format_number(program.time_s[n]) + " s (" + point.describe() + ")");
    state.swap(next);
    out.time_s.push_back(program.time_s[n]);
    out.strain.push_back(strain);
    out.stress.push_back(stress);
  }
  out.final_state = state;
  return out;
}

DriveProgram test_program(const TestCondition& c, const StrainHistory& history) {
  check_strain_history(history);
  DriveProgram p;
  p.time_s = history.time_s;
  if (c.has_temperature()) p.temperature_C.assign(history.time_s.size(), c.temperature_C);
  auto strain_control = [&](int i, std::vector<double> values) {
    p.components[i].imposed = DriveControl::Imposed::strain;
    p.components[i].values = std::move(values);
  };
  if (c.mode == TestMode::bulk) {
    std::vector<double> third(history.strain);
    for (double& x : third) x /= 3.0;
    for (int i = 0; i < 3; ++i) strain_control(i, third);
    for (int i = 3; i < 6; ++i) strain_control(i, {});
    return p;
  }
  const int k = test_component(c);
  for (int i = 0; i < 6; ++i) {
    // Shear: every other strain is zero; uniaxial: the other normal stresses are zero.
    if (i == k) strain_control(i, history.strain);
    else if (c.mode == TestMode::shear || i >= 3) strain_control(i, {});
  }
  return p;
}

std::vector<double> test_stress(const DriveResult& result, const TestCondition& c) {
  std::vector<double> s;
  const int k = c.mode == TestMode::bulk ? -1 : test_component(c);
  for (const Vector6& sigma : result.stress) s.push_back(k < 0 ? sigma.head<3>().mean() : sigma[k]);
  return s;
}

}  // namespace fitlib::model
