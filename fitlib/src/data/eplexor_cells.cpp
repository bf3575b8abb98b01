// libfreexl in a child process (eplexor_cells.hpp): the child opens the workbook, sends the cells
// of the sheets asked for through a pipe (eplexor_wire.cpp) and exits; a child that dies (signal,
// sanitizer report) or answers badly is an InputError naming the file, never a crash of fitlib.
// fork() is safe here because no reader runs on a thread (fitcli reads before any pool starts).
#include <errno.h>
#include <fcntl.h>
#include <freexl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

#include "eplexor_cells.hpp"
#include "fitlib/core/error.hpp"

// Set by the sanitizer runtimes only (a weak reference is null otherwise): libFuzzer registers a
// death callback that would save the input as a finding of the parent when the child dies.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace fitlib::data::xls {
namespace {

// A workbook's cells are at most 65 536 rows × 256 columns; EPLEXOR exports send ~100 kB.
constexpr std::size_t kMaxAnswerBytes = std::size_t{64} << 20;

Cell cell_of(const FreeXL_CellValue& v) {
  Cell cell;
  if (v.type == FREEXL_CELL_INT) cell.kind = Cell::Kind::integer, cell.number = v.value.int_value;
  else if (v.type == FREEXL_CELL_DOUBLE) cell.kind = Cell::Kind::real, cell.number = v.value.double_value;
  else cell.text = v.value.text_value ? v.value.text_value : "";
  return cell;
}

Sheet active_sheet(const void* book, const char* name) {
  Sheet sheet;
  sheet.name = name;
  unsigned short columns = 0;
  freexl_worksheet_dimensions(book, &sheet.rows, &columns);
  sheet.columns = columns;
  for (unsigned r = 0; r < sheet.rows; ++r)
    for (unsigned c = 0; c < sheet.columns; ++c) {
      FreeXL_CellValue v;
      const bool read = freexl_get_cell_value(book, r, static_cast<unsigned short>(c), &v) == FREEXL_OK;
      if (read && v.type != FREEXL_CELL_NULL) sheet.cells[{r, c}] = cell_of(v);
    }
  return sheet;
}

// Runs in the child: the whole answer, or libfreexl's refusal.
std::string workbook_answer(const std::string& path, const std::vector<std::string>& names) {
  const void* book = nullptr;
  const int rc = freexl_open(path.c_str(), &book);
  if (rc != FREEXL_OK) {
    if (book) freexl_close(book);
    return serialize_refusal(rc);
  }
  std::vector<Sheet> sheets;
  unsigned count = 0;
  freexl_get_info(book, FREEXL_BIFF_SHEET_COUNT, &count);
  for (unsigned s = 0; s < count; ++s) {
    const char* name = nullptr;
    if (freexl_get_worksheet_name(book, static_cast<unsigned short>(s), &name) != FREEXL_OK || !name ||
        std::find(names.begin(), names.end(), name) == names.end())
      continue;
    freexl_select_active_worksheet(book, static_cast<unsigned short>(s));
    sheets.push_back(active_sheet(book, name));
  }
  freexl_close(book);
  return serialize_sheets(sheets);
}

bool write_all(int fd, const std::string& bytes) {
  for (std::size_t at = 0; at < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<std::size_t>(n);
  }
  return true;
}

[[noreturn]] void run_child(int fd, const std::function<std::string()>& answer) {
  if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
  const int null = ::open("/dev/null", O_WRONLY);  // libfreexl's (or a sanitizer's) noise stays here
  if (null >= 0) ::dup2(null, STDERR_FILENO);
  bool ok = false;
  try {
    ok = write_all(fd, answer());
  } catch (...) {
  }
  ::_exit(ok ? 0 : 1);  // no atexit handlers, no stdio flush of the parent's buffers
}

// Reads until the child closes the pipe (or sends too much); false when it sent too much.
bool read_answer(int fd, std::string& bytes) {
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    if (bytes.size() + static_cast<std::size_t>(n) > kMaxAnswerBytes) return false;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

// The child's end in words, for the message ("" when it exited normally).
std::string abnormal_end(int status) {
  if (WIFSIGNALED(status)) return "its reader process was killed by signal " + std::to_string(WTERMSIG(status));
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    return "its reader process failed with status " + std::to_string(WEXITSTATUS(status));
  return "";
}

}  // namespace

std::string answer_of_child(const std::string& path, const std::function<std::string()>& answer) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw core::InputError(std::string("libfreexl could not read it (no pipe: ") + std::strerror(errno) + ")", path);
  const pid_t pid = ::fork();
  const int fork_errno = errno;
  if (pid == 0) {
    ::close(fds[0]);
    run_child(fds[1], answer);
  }
  ::close(fds[1]);
  if (pid < 0) {
    ::close(fds[0]);
    throw core::InputError(std::string("libfreexl could not read it (no process: ") + std::strerror(fork_errno) + ")",
                           path);
  }
  std::string bytes;
  bool complete = false;
  try {
    complete = read_answer(fds[0], bytes);
  } catch (...) {  // out of memory: still reap the child
    complete = false;
  }
  ::close(fds[0]);
  if (!complete) ::kill(pid, SIGKILL);
  const std::string end = abnormal_end(wait_for(pid));
  if (!complete) throw core::InputError("libfreexl could not read it (more than 64 MiB of cells)", path);
  if (!end.empty()) throw core::InputError("libfreexl could not read it (" + end + ")", path);
  return bytes;
}

std::vector<Sheet> read_sheets(const std::string& path, const std::vector<std::string>& names) {
  return parse_sheets(answer_of_child(path, [&] { return workbook_answer(path, names); }), path);
}

}  // namespace fitlib::data::xls
