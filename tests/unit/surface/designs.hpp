#pragma once
// Test designs with the level structures of Report V (amplitude, frequency, temperature).
#include <cmath>
#include <functional>
#include <vector>

#include "fitlib/core/rng.hpp"
#include "fitlib/surface/fit.hpp"

namespace fitlib::surface::testing {

inline const std::vector<double> kAmplitudes{0.005, 0.015, 0.045};
inline const std::vector<double> kFrequencies_Hz{3.0, 34.0, 60.0};
inline const std::vector<double> kTemperatures_C{23.0, 60.0, 100.0};

// Level values for a design with the given numbers of levels per axis (taken from the lists above).
inline std::vector<std::vector<double>> levels(int amplitudes, int frequencies, int temperatures) {
  auto first = [](const std::vector<double>& v, int n) {
    if (n == 1) return std::vector<double>{v[1]};
    if (n == 2) return std::vector<double>{v[0], v[2]};
    return v;
  };
  return {first(kAmplitudes, amplitudes), first(kFrequencies_Hz, frequencies),
          first(kTemperatures_C, temperatures)};
}

// A rubber-like storage modulus (MPa): Payne softening with amplitude, a slow rise with log
// frequency, softening with temperature.
inline double rubber_storage_MPa(double amplitude, double frequency_Hz, double temperature_C) {
  return 10.0 * (0.5 + 0.5 / (1.0 + amplitude / 0.015)) * (1.0 + 0.05 * std::log10(frequency_Hz)) *
         (1.0 - 0.005 * (temperature_C - 23.0));
}

using CellFilter = std::function<bool(const std::vector<int>&)>;  // true: the cell has data
using Replicates = std::function<int(std::size_t cell_number)>;    // samples in the n-th cell

// All cells of the level grid that pass `has_data`, each with replicates(n) points, y from f plus
// relative noise.
inline SampleSet make_design(const std::vector<std::vector<double>>& lv, const CellFilter& has_data,
                             const Replicates& replicates, double relative_noise = 0.01,
                             std::uint64_t seed = 7,
                             const std::function<double(const double*)>& f = nullptr) {
  core::Rng rng(seed);
  std::vector<std::vector<double>> rows;
  std::vector<double> ys;
  std::vector<int> index(lv.size(), 0);
  std::size_t cell_number = 0;
  while (true) {
    if (has_data(index)) {
      const int n = replicates(cell_number++);
      for (int r = 0; r < n; ++r) {
        std::vector<double> x(lv.size());
        for (std::size_t k = 0; k < lv.size(); ++k) x[k] = lv[k][static_cast<std::size_t>(index[k])];
        const double y = f ? f(x.data()) : rubber_storage_MPa(x[0], x[1], x[2]);
        rows.push_back(x);
        ys.push_back(y * (1.0 + relative_noise * rng.normal()));
      }
    }
    bool advanced = false;
    for (std::size_t k = lv.size(); k-- > 0 && !advanced;) {
      advanced = ++index[k] < static_cast<int>(lv[k].size());
      if (!advanced) index[k] = 0;
    }
    if (!advanced) break;
  }
  SampleSet data;
  data.x.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(lv.size()));
  data.y.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t k = 0; k < lv.size(); ++k)
      data.x(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = rows[r][k];
    data.y[static_cast<Eigen::Index>(r)] = ys[r];
  }
  data.source = "design";
  return data;
}

inline FitOptions rubber_options() {
  FitOptions o;
  o.axes = {{"strain_amplitude", "", {}, {}},
            {"frequency_Hz", "Hz", {}, {}},
            {"temperature_C", "C", {}, {}}};
  o.dependent_name = "storage_MPa";
  o.dependent_unit = "MPa";
  return o;
}

// Report V's shear design: no test at the largest amplitude with the highest temperature.
inline bool shear_has_data(const std::vector<int>& i) { return !(i[0] == 2 && i[2] == 2); }

}  // namespace fitlib::surface::testing
