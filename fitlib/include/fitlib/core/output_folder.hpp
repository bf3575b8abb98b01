#pragma once
// An output folder checked before any work (`life --out-dir` was first tried after the whole life
// ran: a file at that path, or a folder that cannot be written, failed at the end).
#include <string>

namespace fitlib::core {

// InputError naming `dir` (exit 3, as any output folder that cannot be written) when it is a file,
// an existing folder that is not writable, or when the nearest existing folder above a missing one
// is a file or not writable (so it could not be made). Creates nothing.
void check_output_dir(const std::string& dir);

}  // namespace fitlib::core
