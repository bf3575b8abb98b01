#pragma once
// File output that never leaves a half-written file behind, and content hashing for provenance.
#include <string>

namespace fitlib::core {

// Writes `content` to `path` through a temporary in the same folder and a rename; a special file
// (below) is written in place, its write checked. A symbolic link is written through: its target
// (resolve_links) is replaced, by a temporary in the target's folder, and the link stays a link.
void write_file_atomically(const std::string& path, const std::string& content);

// `path` with its symbolic links followed to the file they name (a chain of links; a relative link
// read from its own folder); a path that is no link comes back as given. A dangling link gives the
// path it names (written through, as the shell's `>` does). InputError naming `path` on a loop.
std::string resolve_links(const std::string& path);

// True when `path` (its symbolic links followed) exists and is no regular file or folder: a device
// such as /dev/full or /dev/null, a FIFO, or /dev/stdout. A rename would replace that node by a
// regular file (as root, /dev/full became one).
bool is_special_file(const std::string& path);

// Checks before any work that `path` can be written: its folder exists and is writable and the
// path is not a folder (for a symbolic link: its target's folder); InputError naming the path otherwise. Commands with several outputs check
// them all first and write them all at the end, so a failed run leaves none behind.
void check_output_path(const std::string& path);

// True when `a` and `b` name one file: the same inode when both exist (hard links, symlinks,
// "./x" and "x"), else the same resolved absolute path (symbolic links followed). "-" (stdin/stdout) is no file.
bool same_file(const std::string& a, const std::string& b);

// Creates the output folder `dir` (and its parents); InputError naming it when that fails.
void prepare_output_dir(const std::string& dir);

// Whole file as bytes; InputError naming the file when it cannot be read.
std::string read_file(const std::string& path);

// Lower-case hex SHA-256 of `bytes`.
std::string sha256_hex(const std::string& bytes);

}  // namespace fitlib::core
