// User constraints of a surface fit (docs/surface.md, JSON), read as `fitcli surface fit
// --constraints` reads them, against a fixed 3-axis shape of degrees 2, 3, 2.
#include <nlohmann/json.hpp>

#include "fitlib/surface/fit.hpp"
#include "fuzz_common.hpp"

namespace {
fitlib::surface::Surface shape() {
  fitlib::surface::Surface s;
  const char* names[] = {"strain_amplitude", "frequency_Hz", "temperature_C"};
  const int degrees[] = {2, 3, 2};
  for (int k = 0; k < 3; ++k) {
    fitlib::surface::Axis axis;
    axis.name = names[k];
    axis.degree = degrees[k];
    s.axes.push_back(axis);
  }
  s.control_points = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.size()));
  return s;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fitlib::surface::Surface s = shape();
  const std::string path = fitlib::fuzz::write_input(data, size, ".json");
  return fitlib::fuzz::run_reader([&] {
    const auto groups = fitlib::surface::parse_user_constraints(
        fitlib::surface::read_user_constraints(path), s, path);
    for (const auto& g : groups)
      for (const auto& c : g.equations) {
        fitlib::fuzz::require_finite(c.rhs, "constraint rhs");
        for (const auto& [index, coefficient] : c.terms) {
          if (index >= s.size()) fitlib::fuzz::finding("constraint index outside the control points");
          fitlib::fuzz::require_finite(coefficient, "constraint coefficient");
        }
      }
  });
}
