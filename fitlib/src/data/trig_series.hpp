#pragma once
// Trigonometric polynomials for the waveform analysis (waveform.hpp steps 1, 3–5):
// p(θ) = c + Σ_{k=1..K} a_k cos kθ + b_k sin kθ, their least-squares basis, extremes, and the
// Gauss–Newton refinement of the drive frequency.
#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace fitlib::data::trig {

struct TrigSeries {
  double c = 0.0;
  Eigen::VectorXd a, b;  // index k−1
  int degree() const { return static_cast<int>(a.size()); }
  double value(double theta) const {
    double v = c;
    for (int k = 1; k <= degree(); ++k) v += a[k - 1] * std::cos(k * theta) + b[k - 1] * std::sin(k * theta);
    return v;
  }
  // dp/dθ and d²p/dθ².
  double slope(double theta) const {
    double v = 0.0;
    for (int k = 1; k <= degree(); ++k) v += k * (b[k - 1] * std::cos(k * theta) - a[k - 1] * std::sin(k * theta));
    return v;
  }
  double curvature(double theta) const {
    double v = 0.0;
    for (int k = 1; k <= degree(); ++k) v -= k * k * (a[k - 1] * std::cos(k * theta) + b[k - 1] * std::sin(k * theta));
    return v;
  }
};

// Columns 1, cos kθ, sin kθ (k = 1..K) at the given phases.
Eigen::MatrixXd trig_basis(const std::vector<double>& theta, int degree);

// The series of least-squares coefficients ordered as trig_basis' columns.
TrigSeries series_from(const Eigen::VectorXd& coefficients, int degree);

// Largest and smallest value over one period.
std::pair<double, double> extremes(const TrigSeries& p);

// Gauss–Newton fit of c + Σ a_k cos kω(t−t0) + b_k sin kω(t−t0) to the whole record, over the
// coefficients and ω together; returns the refined ω (exact for an exact trig polynomial), or
// the start with a warning when it moves by 5 % or more.
double refine_angular_frequency(const std::vector<double>& time_s, const std::vector<double>& y,
                                double omega, int degree, std::vector<std::string>& warnings);

}  // namespace fitlib::data::trig
