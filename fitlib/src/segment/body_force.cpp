// Dead body forces per element (fitlib/segment/load.hpp): the consistent nodal loads
// f_a = ∫ N_a b dV of a force per reference volume b uniform over each element, integrated by the
// element loop's rule (LoadAssembly::add_element_forces). The load cycle's b is Report I's contact
// pressure, friction and radial inertia over the half width B/2, 6.6–6.9 (cycle_loads.cpp).
#include "fitlib/segment/load.hpp"

#include <utility>

namespace fitlib::segment {
namespace {

class DeadBodyForce final : public Load {
 public:
  DeadBodyForce(int elements, ElementForcesAt b) : elements_(elements), b_at_(std::move(b)) {}
  // Dead: a function of λ, evaluated once per load level (not per Newton iteration).
  void prepare(double lambda) override {
    b_.assign(elements_, Eigen::Vector2d::Zero());
    b_at_(lambda, b_);
  }
  void add(LoadAssembly& to) const override { to.add_element_forces(b_); }

 private:
  int elements_;
  ElementForcesAt b_at_;
  std::vector<Eigen::Vector2d> b_;
};

}  // namespace

LoadPtr dead_body_force(int elements, ElementForcesAt b) { return std::make_shared<DeadBodyForce>(elements, std::move(b)); }

}  // namespace fitlib::segment
