#pragma once
// Running a sweep (docs/sweep.md "Running"): the grid is cut into chunks of consecutive cases; an
// executor computes a chunk's rows (threads here, MPI ranks in fitlib/mpi/sweep_mpi.hpp) and
// the writer appends them in case order to FILE.partial, flushed after each chunk, which is
// renamed to FILE when the last case is done. A restart with the same sweep reads the finished
// rows back (hash and case numbers checked, a cut last line dropped) and runs only the rest, so
// the final bytes equal those of an uninterrupted run.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/scene/indexed_run.hpp"
#include "fitlib/scene/sweep.hpp"

namespace fitlib::scene {

// Rows of the cases `cases` (in that order), computed by `threads` threads taking cases as they
// free up. An error other than a case's own bad input or solver failure is rethrown.
std::vector<std::string> sweep_rows_in_threads(const Sweep& sweep, const std::vector<std::size_t>& cases,
                                               int threads);

// Computes the rows of a chunk, on one process or many.
class SweepExecutor {
 public:
  virtual ~SweepExecutor() = default;
  // True on the one process that writes the table (MPI rank 0).
  virtual bool writes() const { return true; }
  // Processes × threads: sets the chunk size.
  virtual int workers() const = 0;
  // The writer's value, known to every process (the resume point, the decision to go on).
  virtual std::size_t share(std::size_t writer_value) { return writer_value; }
  // Rows of cases [begin, end) in case order on the writer; other processes return nothing.
  virtual std::vector<std::string> rows(const Sweep& sweep, std::size_t begin, std::size_t end) = 0;
};

class ThreadExecutor : public SweepExecutor {
 public:
  explicit ThreadExecutor(int threads) : threads_(threads < 1 ? 1 : threads) {}
  int workers() const override { return threads_; }
  std::vector<std::string> rows(const Sweep& sweep, std::size_t begin, std::size_t end) override;

 private:
  int threads_;
};

struct SweepRunOptions {
  std::string out_path;        // result CSV, resumable; empty: the table is only returned
  bool progress = true;        // cases done / total, rate and time left on stderr
  std::size_t stop_after = 0;  // tests: stop as if killed once this many cases are done (0: never)
};

struct SweepRunResult {
  std::string table;          // the whole CSV (comment line, header, rows) on the writer
  std::size_t resumed = 0;    // cases read back from FILE.partial
  bool complete = false;      // false only after stop_after
};

// The first line of the table: "# fitlib sweep sha256=<hash> cases=<N>".
std::string sweep_table_head(const Sweep& sweep);

SweepRunResult run_sweep(const Sweep& sweep, SweepExecutor& executor, const SweepRunOptions& options);

// The table as one JSON document: sweep name, sha256, cases, columns and one object per row
// (numbers as numbers, empty fields as null).
nlohmann::json sweep_json(const Sweep& sweep, const std::string& table);

}  // namespace fitlib::scene
