// Card → modulus grid → surface.
#include "fitlib/surface/card_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::surface {
namespace {

using core::format_number;

double quantity_of(const ModulusGridRow& r, const std::string& quantity) {
  if (quantity == "storage") return r.storage_MPa;
  if (quantity == "loss") return r.loss_MPa;
  if (quantity == "tan_delta") return r.loss_MPa / r.storage_MPa;
  if (quantity == "mean") return r.mean_modulus_MPa;
  throw core::UsageError("unknown quantity '" + quantity + "' (storage, loss, tan_delta, mean)");
}

const char* column_of(const std::string& quantity) {
  return quantity == "storage" ? "storage_MPa"
         : quantity == "loss"  ? "loss_MPa"
         : quantity == "mean"  ? "mean_modulus_MPa"
                               : "tan_delta";
}

}  // namespace

ModulusGrid evaluate_card_grid(const card::Card& card, const CardGridRequest& request) {
  if (request.frequency_Hz.empty()) throw core::UsageError("the grid needs at least one frequency");
  for (double f : request.frequency_Hz)
    if (!(f > 0.0)) throw core::UsageError("frequencies must be positive, got " + format_number(f));
  for (double a : request.strain_amplitude)
    if (!(a >= 0.0)) throw core::UsageError("strain amplitudes must be >= 0, got " + format_number(a));
  const double points = static_cast<double>(request.frequency_Hz.size()) *
                        static_cast<double>(std::max<std::size_t>(1, request.temperature_C.size())) *
                        static_cast<double>(std::max<std::size_t>(1, request.strain_amplitude.size()));
  if (points > kMaxCardGridPoints)
    throw core::InputError("amplitudes x frequencies x temperatures = " + format_number(points) +
                               " points, about " + format_number(points * kCardGridPointCostS, 3) +
                               " s and " + format_number(points * 73 / 1e6, 3) + " MB of CSV, above the work cap " +
                               format_number(kMaxCardGridPoints) + " points (README, work caps); split the grid",
                           "", 0, 0, "grid points");
  ModulusGrid grid;
  grid.request = request;
  grid.card_name = card.name;
  grid.model_kind = card.model_kind;
  const auto model = card.model();
  const auto p = card.values();
  const std::vector<double> amplitudes =
      request.strain_amplitude.empty() ? std::vector<double>{0.0} : request.strain_amplitude;
  const std::vector<double> temperatures =
      request.temperature_C.empty() ? std::vector<double>{std::nan("")} : request.temperature_C;
  for (double amplitude : amplitudes)
    for (double f : request.frequency_Hz)
      for (double T : temperatures) {
        model::TestCondition c;
        c.mode = request.mode;
        c.orientation = request.orientation;
        c.frequency_Hz = f;
        c.temperature_C = T;
        c.strain_amplitude = amplitude;
        const auto m = model->moduli(p.data(), c);
        grid.rows.push_back({amplitude, f, T, m.storage, m.loss, m.mean});
      }
  return grid;
}

std::string modulus_grid_csv(const ModulusGrid& grid) {
  std::ostringstream csv;
  csv << "strain_amplitude,frequency_Hz,temperature_C,storage_MPa,loss_MPa,tan_delta,mean_modulus_MPa\n";
  for (const auto& r : grid.rows) {
    const std::string at = " of the grid at " + core::short_number(r.frequency_Hz) + " Hz";
    core::require_finite(r.storage_MPa, "storage modulus" + at);
    core::require_finite(r.loss_MPa / r.storage_MPa, "tan delta" + at);
    core::require_finite(r.mean_modulus_MPa, "mean modulus" + at);
    csv << format_number(r.strain_amplitude) << "," << format_number(r.frequency_Hz) << ","
        << (std::isnan(r.temperature_C) ? "" : format_number(r.temperature_C)) << "," << format_number(r.storage_MPa)
        << "," << format_number(r.loss_MPa) << "," << format_number(r.loss_MPa / r.storage_MPa) << ","
        << format_number(r.mean_modulus_MPa) << "\n";
  }
  return csv.str();
}

namespace {
struct GridColumn {
  const char* name;
  const char* unit;
  double ModulusGridRow::*member;
};

// The grid's axes in Report V's order, those with values given.
std::vector<GridColumn> grid_columns(const CardGridRequest& rq) {
  std::vector<GridColumn> columns;
  if (!rq.strain_amplitude.empty()) columns.push_back({"strain_amplitude", "", &ModulusGridRow::strain_amplitude});
  columns.push_back({"frequency_Hz", "Hz", &ModulusGridRow::frequency_Hz});
  if (!rq.temperature_C.empty()) columns.push_back({"temperature_C", "C", &ModulusGridRow::temperature_C});
  return columns;
}
}  // namespace

SampleSet grid_samples(const ModulusGrid& grid, const std::string& quantity) {
  const std::vector<GridColumn> columns = grid_columns(grid.request);
  SampleSet data;
  data.source = "grid of card '" + grid.card_name + "'";
  data.x.resize(static_cast<Eigen::Index>(grid.rows.size()), static_cast<Eigen::Index>(columns.size()));
  data.y.resize(static_cast<Eigen::Index>(grid.rows.size()));
  for (std::size_t r = 0; r < grid.rows.size(); ++r) {
    for (std::size_t k = 0; k < columns.size(); ++k)
      data.x(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = grid.rows[r].*(columns[k].member);
    data.y[static_cast<Eigen::Index>(r)] = quantity_of(grid.rows[r], quantity);
  }
  return data;
}

Surface surface_from_grid(const ModulusGrid& grid, const std::string& quantity,
                          const std::vector<int>& degrees) {
  const auto& rq = grid.request;
  const std::vector<GridColumn> columns = grid_columns(rq);
  if (!degrees.empty() && degrees.size() != columns.size())
    throw core::UsageError("give one degree per grid axis (" + std::to_string(columns.size()) + ")");
  const SampleSet data = grid_samples(grid, quantity);
  FitOptions options;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    AxisSpec axis{columns[k].name, columns[k].unit, {}, {}};
    if (!degrees.empty()) axis.degree = degrees[k];
    options.axes.push_back(axis);
  }
  options.dependent_name = column_of(quantity);
  options.dependent_unit = quantity == "tan_delta" ? "" : "MPa";
  options.name = grid.card_name + " " + quantity + " (" + model::to_string(rq.mode) +
                 (rq.orientation.empty() ? "" : " " + rq.orientation) + ")";
  // A designed grid: every distinct value is a level (the user chose them).
  options.level_tolerance = 0.0;
  // Moduli over decades of frequency: a polynomial in the values themselves swings below zero
  // between the levels (a Prony card's loss over 0.1–100 Hz and −20–80 °C reached −0.87 MPa), one
  // in their log10 cannot; a grid with a value ≤ 0 stays linear (docs/surface.md "Command line").
  if ((data.y.array() > 0.0).all()) options.dependent_transform = Transform::log10;
  Surface s = fit_surface(data, options);
  s.provenance = {{"card", grid.card_name},
                  {"model", grid.model_kind},
                  {"mode", model::to_string(rq.mode)},
                  {"orientation", rq.orientation},
                  {"quantity", quantity}};
  return s;
}

}  // namespace fitlib::surface
