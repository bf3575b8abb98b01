// The chunked run of a sweep: resumable result file, progress, rows in case order.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/scene/sweep_run.hpp"

namespace fitlib::scene {
namespace {

std::string head_text(const Sweep& sweep) {
  std::string head = sweep_table_head(sweep) + "\n";
  const auto fields = sweep_header(sweep);
  for (std::size_t i = 0; i < fields.size(); ++i) head += (i ? "," : "") + csv_field(fields[i]);
  return head + "\n";
}

// Finished rows of FILE.partial: its head must be this sweep's; row k must be case k; a cut last
// line is dropped. Returns the case count and keeps the bytes in `table`.
std::size_t read_partial(const std::string& partial, const std::string& head, std::size_t case_count,
                         std::string& table) {
  const std::string bytes = core::read_file(partial);
  if (bytes.size() < head.size() && head.compare(0, bytes.size(), bytes) == 0) {  // cut in the head
    table = head;
    return 0;
  }
  if (bytes.compare(0, head.size(), head) != 0)
    throw core::InputError("the unfinished result file was written for another sweep or other input files "
                           "(its first lines differ); remove it to start over",
                           partial, 1, 1);
  std::size_t done = 0, pos = head.size();
  for (std::size_t nl; (nl = bytes.find('\n', pos)) != std::string::npos; pos = nl + 1, ++done) {
    const std::string expect = std::to_string(done) + ",";
    if (bytes.compare(pos, expect.size(), expect) != 0)
      throw core::InputError("expected the row of case " + std::to_string(done) + "; remove the file to start over",
                             partial, static_cast<int>(done + 3), 1);
  }
  if (done > case_count)
    throw core::InputError("holds more rows than the sweep has cases; remove it to start over", partial, 1, 1);
  table = bytes.substr(0, pos);
  return done;
}

class ProgressLine {
 public:
  ProgressLine(bool on, std::size_t total, std::size_t start) : on_(on), total_(total), start_(start) {}
  void update(std::size_t done, bool last) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - t0_).count();
    if (!last && std::chrono::duration<double>(now - shown_).count() < 1.0) return;
    shown_ = now;
    const double rate = elapsed > 0 ? static_cast<double>(done - start_) / elapsed : 0.0;
    std::cerr << "sweep: " << done << "/" << total_ << " cases, " << core::format_number(rate, 3) << " cases/s";
    if (rate > 0 && done < total_)
      std::cerr << ", " << core::format_number(static_cast<double>(total_ - done) / rate, 3) << " s left";
    std::cerr << "\n";
  }

 private:
  bool on_;
  std::size_t total_, start_;
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now(), shown_ = t0_;
};

}  // namespace

std::string sweep_table_head(const Sweep& sweep) {
  return "# fitlib sweep sha256=" + sweep.sha256 + " cases=" + std::to_string(sweep.case_count);
}

SweepRunResult run_sweep(const Sweep& sweep, SweepExecutor& ex, const SweepRunOptions& opt) {
  SweepRunResult result;
  const bool writer = ex.writes(), to_file = writer && !opt.out_path.empty();
  const std::string head = head_text(sweep), partial = opt.out_path + ".partial";
  std::size_t done = 0;
  if (to_file) {
    core::check_output_path(opt.out_path);
    if (std::filesystem::exists(partial)) done = read_partial(partial, head, sweep.case_count, result.table);
    else result.table = head;
    core::write_file_atomically(partial, result.table);  // drops a cut last line
  } else if (writer) {
    result.table = head;
  }
  done = ex.share(done);
  result.resumed = done;
  std::ofstream out;
  if (to_file) out.open(partial, std::ios::binary | std::ios::app);
  ProgressLine progress(writer && opt.progress, sweep.case_count, done);
  // Chunks start at 4 cases per worker and double while one takes under a second (fewer waits
  // at chunk ends for fast cases, a flushed row soon for slow ones); the writer's size is shared.
  std::size_t chunk = 4 * static_cast<std::size_t>(ex.workers());
  while (done < sweep.case_count) {
    std::size_t end = std::min(sweep.case_count, done + chunk);
    if (opt.stop_after > done) end = std::min(end, opt.stop_after);
    const auto t0 = std::chrono::steady_clock::now();
    std::string text;
    for (const auto& row : ex.rows(sweep, done, end)) text += row + "\n";
    if (to_file && !(out << text << std::flush))
      throw core::InputError("cannot append to the result file", partial);
    result.table += text;
    done = end;
    progress.update(done, done == sweep.case_count);
    const bool stop = opt.stop_after > 0 && done >= opt.stop_after && done < sweep.case_count;
    if (ex.share(stop ? 1 : 0)) return result;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 1.0 && chunk < 4096) chunk *= 2;
    chunk = ex.share(chunk);
  }
  result.complete = true;
  if (to_file) {
    out.close();
    std::filesystem::rename(partial, opt.out_path);
  }
  return result;
}

}  // namespace fitlib::scene
