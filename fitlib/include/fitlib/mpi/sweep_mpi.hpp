#pragma once
// Sweeps and the life's card draws across MPI ranks (docs/sweep.md "MPI"): built only when CMake
// finds MPI (FITLIB_MPI). Case (draw) i runs on rank i mod N (with that rank's threads); rank 0
// gathers the sweep's rows and writes them in case order, every rank gathers the draws' lives, so
// neither depends on N.
#include "fitlib/scene/indexed_run.hpp"
#include "fitlib/scene/sweep_run.hpp"

namespace fitlib::mpi {

// True when this process was started by mpirun/mpiexec (OpenMPI's or a PMI launcher's
// environment); fitcli then joins the MPI job, else it runs on one process with threads.
bool launched_by_mpirun();

// MPI_Init / MPI_Finalize for the lifetime of the object.
class Session {
 public:
  Session();
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

class MpiExecutor : public scene::SweepExecutor {
 public:
  MpiExecutor(const Session& session, int threads);
  bool writes() const override { return rank_ == 0; }
  int workers() const override { return size_ * threads_; }
  std::size_t share(std::size_t writer_value) override;
  std::vector<std::string> rows(const scene::Sweep& sweep, std::size_t begin, std::size_t end) override;

 private:
  int rank_, size_, threads_;
};

// The card draws of [life] uncertainty = "cards" (Scene::draw_executor) across the ranks: draw k on
// rank k mod N with `threads` threads; every rank gets every draw's text, so every rank computes the
// same intervals (fitcli life writes on rank 0 only).
class MpiIndexedExecutor : public scene::IndexedExecutor {
 public:
  MpiIndexedExecutor(const Session& session, int threads);
  std::vector<std::string> texts(std::size_t n, int threads,
                                 const std::function<std::string(std::size_t)>& work) override;

 private:
  int rank_, size_, threads_;
};

}  // namespace fitlib::mpi
