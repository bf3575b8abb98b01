#pragma once
// CRTP base that turns one templated evaluation into the Model interface's value and Jacobian.
// Derived must provide
//   template <typename T> Moduli<T> evaluate(const T* p, const TestCondition& c) const;
// written with plain arithmetic and std::complex<T>, so T = double and T = ceres::Jet both work.
#include <ceres/jet.h>

#include <vector>

#include "fitlib/model/model.hpp"

namespace fitlib::model {

template <class Derived>
class AutodiffModel : public Model {
 public:
  Moduli<double> moduli(const double* p, const TestCondition& c) const override {
    return self().template evaluate<double>(p, c);
  }

  Moduli<double> moduli(const double* p, const TestCondition& c,
                        Eigen::Ref<Eigen::MatrixXd> jacobian) const override {
    constexpr int kStride = 8;  // derivatives per pass, as Ceres's dynamic autodiff does
    using Jet = ceres::Jet<double, kStride>;
    const int n = static_cast<int>(this->size());
    if (n == 0) return moduli(p, c);
    std::vector<Jet> pj(n);
    Moduli<double> value{};
    for (int start = 0; start < n; start += kStride) {
      for (int i = 0; i < n; ++i) {
        pj[i] = Jet(p[i]);
        if (i >= start && i < start + kStride) pj[i].v[i - start] = 1.0;
      }
      const Moduli<Jet> m = self().template evaluate<Jet>(pj.data(), c);
      for (int i = start; i < n && i < start + kStride; ++i) {
        jacobian(0, i) = m.storage.v[i - start];
        jacobian(1, i) = m.loss.v[i - start];
        jacobian(2, i) = m.mean.v[i - start];
      }
      value = {m.storage.a, m.loss.a, m.mean.a};
    }
    return value;
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

}  // namespace fitlib::model
