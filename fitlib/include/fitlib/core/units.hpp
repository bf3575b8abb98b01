#pragma once
// Internal units, chosen once: stress and moduli in MPa, length in mm, force in N, time in s,
// temperature in °C, frequency in Hz (angular frequency in rad/s where the name says so).
#include <string>

namespace fitlib::core {

constexpr double kPi = 3.14159265358979323846;
constexpr double kZeroCelsiusInKelvin = 273.15;

// Factor that converts a modulus given in `unit` (Pa, kPa, MPa, GPa) to MPa.
// Throws InputError (naming the unit) for anything else.
double modulus_to_MPa(const std::string& unit);

inline double celsius_from_kelvin(double t_K) { return t_K - kZeroCelsiusInKelvin; }
inline double kelvin_from_celsius(double t_C) { return t_C + kZeroCelsiusInKelvin; }
inline double angular_frequency(double f_Hz) { return 2.0 * kPi * f_Hz; }

}  // namespace fitlib::core
