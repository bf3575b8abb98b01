// The chunked run of a sweep: resumable result file, progress, rows in case order.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "fitlib/core/error.hpp"
#include "fitlib/core/file_lock.hpp"
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

// FILE.partial is the table with one more column, row_sha256: the first 16 hex digits of the
// SHA-256 of the sweep's hash (of the sweep file and every scene and card it names: the case's
// inputs) and the row (its case number and results). A resumed row that was edited or damaged
// (a number changed, a nan) is then refused at its line instead of reaching the final file.
std::string row_checksum(const Sweep& sweep, const std::string& row) {
  return core::sha256_hex(sweep.sha256 + "\n" + row).substr(0, 16);
}

std::string partial_head(const std::string& head) { return head.substr(0, head.size() - 1) + ",row_sha256\n"; }

std::string partial_rows(const Sweep& sweep, const std::vector<std::string>& rows) {
  std::string text;
  for (const auto& row : rows) text += row + "," + row_checksum(sweep, row) + "\n";
  return text;
}

// The finished rows of FILE.partial, verified: its head must be this sweep's; row k must be case
// k with its checksum; a cut last line is dropped. Returns the case count; the table's rows (without
// the checksums) go to `table`, the lines kept to `kept`.
std::size_t read_partial(const std::string& partial, const Sweep& sweep, const std::string& head,
                         std::string& table, std::string& kept) {
  const std::string bytes = core::read_file(partial), phead = partial_head(head);
  table = head;
  kept = phead;
  if (bytes.size() < phead.size() && phead.compare(0, bytes.size(), bytes) == 0) return 0;  // cut in the head
  if (bytes.compare(0, phead.size(), phead) != 0)
    throw core::InputError("the unfinished result file was written for another sweep or other input files "
                           "(its first lines differ); remove it to start over",
                           partial, 1, 1);
  std::size_t done = 0, pos = phead.size();
  for (std::size_t nl; (nl = bytes.find('\n', pos)) != std::string::npos; pos = nl + 1, ++done) {
    const int line = static_cast<int>(done + 3);
    const std::string text = bytes.substr(pos, nl - pos), expect = std::to_string(done) + ",";
    if (done >= sweep.case_count)
      throw core::InputError("holds more rows than the sweep has cases; remove it to start over", partial, line, 1);
    if (text.compare(0, expect.size(), expect) != 0)
      throw core::InputError("expected the row of case " + std::to_string(done) + "; remove the file to start over",
                             partial, line, 1);
    const auto comma = text.rfind(',');
    const std::string row = text.substr(0, comma);
    if (comma == std::string::npos || text.substr(comma + 1) != row_checksum(sweep, row))
      throw core::InputError("the row of case " + std::to_string(done) +
                                 " does not match its row_sha256 (the file was edited or damaged); remove it "
                                 "to start over",
                             partial, line, static_cast<int>(comma == std::string::npos ? 1 : comma + 2));
    table += row + "\n";
    kept += text + "\n";
  }
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

// The result file (and its .partial and .lock) may be none of the files the sweep reads: the sweep file,
// its scenes and cards (fitcli refuses --out = --sweep too; the scenes are named inside).
void refuse_output_on_input(const Sweep& sweep, const std::string& out) {
  std::vector<std::string> inputs = sweep.scenes;
  inputs.push_back(sweep.path);
  inputs.insert(inputs.end(), sweep.card_files.begin(), sweep.card_files.end());
  for (const auto& in : inputs)
    for (const std::string& written : {out, out + ".partial", out + ".lock"})  // the lock's holder removes it
      if (core::same_file(written, in))
        throw core::InputError("the result file would replace " + in + ", which the sweep reads; write elsewhere",
                               written);
}

// A device, FIFO or /dev/stdout as the result file: its FILE.partial and FILE.lock would be made
// beside it (in /dev), and as root the final rename replaced /dev/full by a regular file.
// (A folder is refused before, by core::check_output_path.)
void refuse_special_output(const std::string& out) {
  if (core::is_special_file(out))
    throw core::InputError("the result file must be a regular file (its .partial and .lock are made beside it); "
                           "without --out the table goes to stdout", out);
}

}  // namespace

std::string sweep_table_head(const Sweep& sweep) {
  return "# fitlib sweep sha256=" + sweep.sha256 + " cases=" + std::to_string(sweep.case_count);
}

SweepRunResult run_sweep(const Sweep& sweep, SweepExecutor& ex, const SweepRunOptions& opt) {
  SweepRunResult result;
  const bool writer = ex.writes(), to_file = writer && !opt.out_path.empty();
  // A symbolic link as the result file: its .partial and .lock go beside the target the result
  // replaces (core::write_file_atomically), so two spellings of one file share one lock.
  const std::string out_path = to_file ? core::resolve_links(opt.out_path) : opt.out_path;
  const std::string head = head_text(sweep), partial = out_path + ".partial";
  std::size_t done = 0;
  std::unique_ptr<core::OutputLock> lock;
  if (to_file) {
    core::check_output_path(out_path);
    refuse_special_output(out_path);
    refuse_output_on_input(sweep, out_path);
    lock = std::make_unique<core::OutputLock>(out_path);
    std::string kept = partial_head(head);
    if (std::filesystem::exists(partial)) done = read_partial(partial, sweep, head, result.table, kept);
    else result.table = head;
    core::write_file_atomically(partial, kept);  // drops a cut last line
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
    const auto rows = ex.rows(sweep, done, end);
    for (const auto& row : rows) text += row + "\n";
    if (to_file && !(out << partial_rows(sweep, rows) << std::flush))
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
  if (to_file) {  // the table without the checksums, then the partial goes
    out.close();
    core::write_file_atomically(out_path, result.table);
    std::filesystem::remove(partial);
  }
  return result;
}

}  // namespace fitlib::scene
