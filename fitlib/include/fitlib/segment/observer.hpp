#pragma once
// What watches a segment solve (solver.hpp): an observer is called after each converged load
// increment with its stresses, displacements and reactions — monitored points, the equilibrium
// check, field output, progress (segment/cycle.cpp composes them). It reads; it never changes the
// problem, so a run with or without an observer converges alike.
#include <functional>
#include <utility>

namespace fitlib::segment {

struct StaticSolution;

class IncrementObserver {
 public:
  virtual ~IncrementObserver() = default;
  // `lambda`: the increment's load level; `increment.increments` its number (1-based).
  virtual void converged(double lambda, const StaticSolution& increment) = 0;
};

// An observer from a function (a test's or a script's probe).
class CallbackObserver : public IncrementObserver {
 public:
  using Callback = std::function<void(double lambda, const StaticSolution& increment)>;
  explicit CallbackObserver(Callback callback) : callback_(std::move(callback)) {}
  void converged(double lambda, const StaticSolution& increment) override { callback_(lambda, increment); }

 private:
  Callback callback_;
};

}  // namespace fitlib::segment
