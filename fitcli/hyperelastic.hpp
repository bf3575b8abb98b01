#pragma once
// fitcli's hyperelastic paths (cmd_hyperelastic.cpp, docs/hyperelastic.md): fit of quasi-static
// tables, eval over stretches, the stress–stretch figure. The commands fit, eval and plot call
// these when the model or card is hyperelastic (model::Model::hyperelastic).
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"

namespace fitcli {

struct HyperelasticFitArgs {
  std::vector<std::string> data;
  std::string model, out, name, plot, residual = "relative", command_line;
  int terms = 0;  // 0: the model's default
  bool compressible = false, json = false;
  std::vector<std::string> mode_weights;  // "planar=2"
  std::vector<double> stability_range;    // {min, max} stretch
  int multistart = 0, max_iterations = 500;
  unsigned long long seed = 1;
};
void run_hyperelastic_fit(const HyperelasticFitArgs& a);

// CSV mode,<abscissa>,nominal_stress_MPa,cauchy_stress_MPa (or JSON rows).
void run_hyperelastic_eval(const fitlib::card::Card& card, const std::string& card_path, const std::string& mode,
                           const std::vector<double>& abscissae, const std::string& out, bool json);

// Stress against stretch per mode (data points, card lines) and the relative residuals.
void plot_hyperelastic(const fitlib::card::Card& card, const std::vector<std::string>& data, const std::string& title,
                       const std::string& out);

}  // namespace fitcli
