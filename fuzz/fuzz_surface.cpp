// Bezier surfaces (formats.md §4, JSON), read from a file as `fitcli surface eval` reads them,
// then evaluated with gradient at the centre of the box (the value must be finite).
#include <vector>

#include "fitlib/surface/surface.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fitlib::fuzz::write_input(data, size, ".json");
  return fitlib::fuzz::run_reader([&] {
    const auto s = fitlib::surface::load_surface(path);
    for (int k = 0; k < s.control_points.size(); ++k)
      fitlib::fuzz::require_finite(s.control_points[k], "control point");
    if (s.size() != static_cast<std::size_t>(s.control_points.size()))
      fitlib::fuzz::finding("control point count differs from the product of (degree + 1)");
    std::vector<double> x;
    for (const auto& axis : s.axes) {
      fitlib::fuzz::require_finite(axis.start, "axis start");
      fitlib::fuzz::require_finite(axis.end, "axis end");
      x.push_back(axis.transform == fitlib::surface::Transform::log10 ? std::sqrt(axis.start * axis.end)
                                                                     : 0.5 * (axis.start + axis.end));
    }
    if (x.empty()) return;
    const auto e = s.evaluate(x.data(), true);
    fitlib::fuzz::require_finite(e.value, "surface value");
  });
}
