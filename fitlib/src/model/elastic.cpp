// Linear elastic cards: isotropic (E, ν) and orthotropic (engineering constants in material axes).
#include "fitlib/model/elastic.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/model/autodiff_model.hpp"
#include "fitlib/model/material_point.hpp"
#include "points.hpp"

namespace fitlib::model {
namespace {

using core::ParameterSpec;
using core::Transform;
constexpr double kInf = std::numeric_limits<double>::infinity();

ParameterSpec modulus(const std::string& name, double start) {
  return {name, "MPa", 0.0, kInf, Transform::log, "elastic", start, false};
}
ParameterSpec poisson(const std::string& name, double lower, double upper, double start) {
  return {name, "-", lower, upper, Transform::linear, "elastic", start, false};
}

// Compliance of the normal block (Voigt 11, 22, 33) and the shear compliances 1/G23, 1/G13,
// 1/G12, from the parameters in the order of elastic.hpp.
template <typename T>
void compliance(const T* p, bool orthotropic, T S[3][3], T shear[3]) {
  if (!orthotropic) {  // E, ν
    const T E = p[0], nu = p[1];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S[i][j] = (i == j ? T(1.0) : -nu) / E;
    for (int k = 0; k < 3; ++k) shear[k] = T(2.0) * (T(1.0) + nu) / E;
    return;
  }
  const T E[3] = {p[0], p[1], p[2]};
  // S_ij = −ν_ij/E_i for i < j (symmetric: ν_ij/E_i = ν_ji/E_j).
  S[0][0] = T(1.0) / E[0], S[1][1] = T(1.0) / E[1], S[2][2] = T(1.0) / E[2];
  S[0][1] = S[1][0] = -p[3] / E[0];
  S[0][2] = S[2][0] = -p[4] / E[0];
  S[1][2] = S[2][1] = -p[5] / E[1];
  shear[0] = T(1.0) / p[8], shear[1] = T(1.0) / p[7], shear[2] = T(1.0) / p[6];
}

// (1/9) Σ C_ij over the normal block: mean stress per volume strain for ε = θ/3 (1, 1, 1).
template <typename T>
T bulk_from_compliance(const T S[3][3]) {
  const T c00 = S[1][1] * S[2][2] - S[1][2] * S[2][1], c01 = S[1][2] * S[2][0] - S[1][0] * S[2][2],
          c02 = S[1][0] * S[2][1] - S[1][1] * S[2][0];
  const T det = S[0][0] * c00 + S[0][1] * c01 + S[0][2] * c02;
  const T c11 = S[0][0] * S[2][2] - S[0][2] * S[2][0], c12 = S[0][2] * S[1][0] - S[0][0] * S[1][2],
          c22 = S[0][0] * S[1][1] - S[0][1] * S[1][0];
  return (c00 + c11 + c22 + T(2.0) * (c01 + c02 + c12)) / (T(9.0) * det);
}

class ElasticModel final : public AutodiffModel<ElasticModel> {
 public:
  explicit ElasticModel(bool orthotropic) : orthotropic_(orthotropic) {
    if (!orthotropic) {
      specs_ = {modulus("E", 10.0), poisson("nu", -0.999, 0.4999, 0.45)};
      return;
    }
    for (const char* n : {"E1", "E2", "E3"}) specs_.push_back(modulus(n, 10.0));
    for (const char* n : {"nu12", "nu13", "nu23"}) specs_.push_back(poisson(n, -1.0, 1.0, 0.3));
    for (const char* n : {"G12", "G13", "G23"}) specs_.push_back(modulus(n, 4.0));
  }

  std::string kind() const override { return orthotropic_ ? "elastic-ortho" : "elastic-iso"; }
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  nlohmann::json options() const override { return nlohmann::json::object(); }
  TestMode native_mode() const override { return TestMode::uniaxial; }

  double bulk_modulus(const double* p) const override {
    return orthotropic_ ? std::numeric_limits<double>::quiet_NaN()
                        : p[0] / (3.0 * (1.0 - 2.0 * p[1]));
  }

  template <typename T>
  Moduli<T> evaluate(const T* p, const TestCondition& c) const {
    T S[3][3], shear[3];
    compliance(p, orthotropic_, S, shear);
    T m;
    if (c.mode == TestMode::bulk) {
      m = bulk_from_compliance(S);
    } else {
      const int k = component(c);
      m = k < 3 ? T(1.0) / S[k][k] : T(1.0) / shear[k - 3];
    }
    return {m, T(0.0), m};
  }

  std::vector<double> stress_response(const double* p, const TestCondition& c,
                                      const StrainHistory& history) const override {
    check_strain_history(history);
    const double m = moduli(p, c).storage;
    std::vector<double> s(history.strain);
    for (double& x : s) x *= m;
    return s;
  }
  double relaxation_modulus(const double* p, const TestCondition& c, double) const override {
    return moduli(p, c).storage;
  }
  double creep_compliance(const double* p, const TestCondition& c, double) const override {
    return 1.0 / moduli(p, c).storage;
  }

  std::shared_ptr<const MaterialPoint> material_point(const double* p,
                                                      const PointOptions&) const override {
    double S[3][3], shear[3];
    compliance(p, orthotropic_, S, shear);
    Matrix6 compliance6 = Matrix6::Zero();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) compliance6(i, j) = S[i][j];
      compliance6(3 + i, 3 + i) = shear[i];
    }
    const Eigen::LLT<Matrix6> llt(compliance6);
    if (llt.info() != Eigen::Success || !compliance6.allFinite())
      throw core::UsageError(kind() + ": the elastic constants give no positive definite "
                             "stiffness (check the Poisson ratios)");
    return points::elastic_point(llt.solve(Matrix6::Identity()), kind());
  }

 private:
  // Voigt index of the test: uniaxial 11/22/33 → 0–2, shear 23/13/12 → 3–5; isotropic
  // default 22 / 12.
  int component(const TestCondition& c) const {
    const std::string& o = c.orientation;
    if (o.empty()) {
      if (orthotropic_) throw core::UsageError("elastic-ortho needs the test orientation");
      return c.mode == TestMode::uniaxial ? 1 : 5;
    }
    if (o.size() != 2 || o[0] < '1' || o[0] > '3' || o[1] < '1' || o[1] > '3')
      throw core::UsageError(kind() + ": orientation '" + o + "' is not 11, 22, 33, 12, 13 or 23");
    const int i = o[0] - '1', j = o[1] - '1';
    if ((c.mode == TestMode::uniaxial) != (i == j))
      throw core::UsageError(kind() + ": orientation '" + o + "' does not fit a " +
                             to_string(c.mode) + " test");
    return i == j ? i : (i + j == 3) ? 3 : (i + j == 2) ? 4 : 5;
  }

  bool orthotropic_;
  std::vector<ParameterSpec> specs_;
};

}  // namespace

bool is_elastic_kind(const std::string& kind) {
  return kind == "elastic-iso" || kind == "elastic-ortho";
}

ModelPtr make_elastic_model(const std::string& kind, const nlohmann::json& options) {
  if (!is_elastic_kind(kind)) throw core::UsageError("not an elastic model kind: '" + kind + "'");
  if (!options.is_null() && !(options.is_object() && options.empty()))
    throw core::UsageError(kind + " takes no model options");
  return std::make_shared<ElasticModel>(kind == "elastic-ortho");
}

}  // namespace fitlib::model
