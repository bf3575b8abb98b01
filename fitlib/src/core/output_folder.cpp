#include "fitlib/core/output_folder.hpp"

#include <unistd.h>

#include <filesystem>

#include "fitlib/core/error.hpp"

namespace fitlib::core {

void check_output_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path p = fs::absolute(dir.empty() ? "." : dir, ec).lexically_normal();
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) throw InputError("output folder is a file, not a folder", dir);
    if (::access(p.c_str(), W_OK) != 0) throw InputError("output folder is not writable", dir);
    return;
  }
  // The first existing path above: the folder would be made inside it.
  while (p.has_relative_path() && !fs::exists(p, ec)) p = p.parent_path();
  if (!fs::is_directory(p, ec))
    throw InputError("cannot create output folder (" + p.string() + " is a file, not a folder)", dir);
  if (::access(p.c_str(), W_OK) != 0)
    throw InputError("cannot create output folder (" + p.string() + " is not writable)", dir);
}

}  // namespace fitlib::core
