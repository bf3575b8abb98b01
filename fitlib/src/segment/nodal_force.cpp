// Dead nodal forces (fitlib/segment/load.hpp): a force per node, per mm of width, given as a
// function of λ; the load cycle's are the sheared end faces' traction σ12 along each end's radial
// line, f_a = ∫ N_a σ12 dl (end_faces.hpp; cycle_loads.cpp).
#include "fitlib/segment/load.hpp"

#include <utility>

namespace fitlib::segment {
namespace {

class DeadNodalForce final : public Load {
 public:
  explicit DeadNodalForce(NodeForcesAt f) : f_at_(std::move(f)) {}
  void prepare(double lambda) override { f_at_(lambda, f_); }  // dead: once per load level
  void add(LoadAssembly& to) const override {
    for (std::size_t n = 0; n < f_.size(); ++n) to.add_node_force(static_cast<int>(n), -f_[n]);  // external
  }

 private:
  NodeForcesAt f_at_;
  std::vector<Eigen::Vector2d> f_;
};

}  // namespace

LoadPtr dead_nodal_force(NodeForcesAt f) { return std::make_shared<DeadNodalForce>(std::move(f)); }

}  // namespace fitlib::segment
