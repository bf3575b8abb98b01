#include "fitlib/core/parameter.hpp"

namespace fitlib::core {

int find_parameter(const std::vector<ParameterSpec>& specs, const std::string& name) {
  for (size_t i = 0; i < specs.size(); ++i)
    if (specs[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace fitlib::core
