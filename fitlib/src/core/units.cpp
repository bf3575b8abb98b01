#include "fitlib/core/units.hpp"

#include "fitlib/core/error.hpp"

namespace fitlib::core {

double modulus_to_MPa(const std::string& unit) {
  if (unit == "Pa") return 1e-6;
  if (unit == "kPa") return 1e-3;
  if (unit == "MPa") return 1.0;
  if (unit == "GPa") return 1e3;
  throw InputError("unknown modulus unit '" + unit + "' (expected Pa, kPa, MPa or GPa)");
}

}  // namespace fitlib::core
