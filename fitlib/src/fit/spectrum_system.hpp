#pragma once
// Private to the fit module: the penalised linear system of the smooth spectrum (docs/fitting.md
// "Default: a smooth spectrum") for one placement of the temperature law, its solves along the
// λ path, and the refinement of the law's constants by variable projection.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "admissible.hpp"
#include "backends.hpp"
#include "fitlib/fit/problem.hpp"
#include "fitlib/fit/spectrum.hpp"

namespace fitlib::fit::detail {

// The values of the parameters that are neither term moduli nor times (relaxed modulus, law
// constants, ...), in model order: the same list for every term count of a series model.
std::vector<double> non_series_values(const model::Model& m, const std::vector<double>& p);
// Writes such a list into `p` of model `m` (the inverse of non_series_values).
void set_non_series_values(const model::Model& m, const std::vector<double>& values, std::vector<double>& p);

// A tall least-squares problem reduced by one QR to its square factor: ‖A y − b‖² =
// ‖R y − c‖² + outside, so every λ and active set works on the small R.
struct Reduced {
  Eigen::MatrixXd r;
  Eigen::VectorXd c;
  double outside = 0.0;
};
Reduced reduce(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

// The normal equations of the penalised problem: G = RᵀR, H = DᵀD, rhs = Rᵀc.
struct NormalEquations {
  Eigen::MatrixXd g, h;
  Eigen::VectorXd rhs;
};
NormalEquations normal_equations(const Reduced& red, const Eigen::MatrixXd& d);

// min ‖R y − c‖² + λ‖D y‖² over y ≥ 0: an active set on (G + λH) y = rhs, warm-started from
// `passive` (the positive set of a neighbouring λ; updated; null: start from every column),
// with nnls() on the stacked system when it does not settle.
Eigen::VectorXd solve_penalised(const Reduced& red, const Eigen::MatrixXd& d, const NormalEquations& ne,
                                double lambda, std::vector<bool>* passive);
Eigen::VectorXd solve_penalised(const Reduced& red, const Eigen::MatrixXd& d, double lambda);

// The dense model's linear system: design (columns scaled to unit norm at construction, the
// scale kept when the law moves), its reduction, the zero-padded second-difference operator.
struct SpectrumSystem {
  explicit SpectrumSystem(Problem p) : problem(std::move(p)) {}
  Problem problem;          // the dense model; free = its linear parameters
  LinearDesign design;
  Eigen::VectorXd scale;    // y = scale ⊙ x
  Reduced red;
  Eigen::MatrixXd d;
  NormalEquations normal;   // of red and d
  std::vector<int> column_of_term;  // column of each term's modulus (−1: none)
  SeriesTerms series;
  int terms = 0;
  // Rebuilds design and reduction at the current problem.natural() (scale kept).
  void relinearise();
  // ‖R y − c‖² + outside + λ‖D y‖² at y.
  double penalised(const Eigen::VectorXd& y, double lambda) const;
};

// `dense` with `n` log-spaced times over [tau_lo, tau_hi]; `held` gives the values of the
// parameters that are neither moduli nor times (law constants, ...) — empty: the model's start.
SpectrumSystem make_spectrum_system(const model::ModelPtr& dense, const data::DynamicTestTable& table,
                                    const FitOptions& options, double tau_lo, double tau_hi,
                                    const std::vector<double>& held);

struct PathPoint {
  Eigen::VectorXd y;
  SpectrumPathRow row;
};
// One solve at λ with its GCV figures (warm start as solve_penalised).
PathPoint solve_at(const SpectrumSystem& s, double lambda, std::vector<bool>* passive = nullptr);

// The law's constants (TemperatureLawInfo::shift_parameters) of the system's model moved to
// minimise the penalised objective with λ held, the moduli projected out (re-solved at every
// trial): LN_BOBYQA in fitted coordinates within the problem's bounds. Returns evaluations.
int refine_law_constants(SpectrumSystem& s, double lambda, const std::vector<int>& constants);

}  // namespace fitlib::fit::detail
