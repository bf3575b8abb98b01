// core::write_file_atomically on a path that is no regular file (issue 37 audit): `--out /dev/full`
// and `--out /dev/stdout` exited 0, and as root the rename replaced the device (or the /dev/stdout
// link) by a regular file. A FIFO in this process's own folder stands in for the device here, so a
// wrong implementation replaces the FIFO, never a node of /dev.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"

namespace fitlib::core {
namespace {

namespace fs = std::filesystem;

fs::path own_folder() {
  const fs::path dir = fs::temp_directory_path() / ("fitlib-io-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(AtomicWrite, AFifoOrALinkToItIsWrittenInPlaceAndStaysAFifo) {
  const fs::path dir = own_folder(), fifo = dir / "pipe", link = dir / "link";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink(fifo, link);
  for (const fs::path& target : {fifo, link}) {
    auto reader = std::async(std::launch::async, [&] { return read_all(fifo); });
    write_file_atomically(target.string(), "a,b\n1,2\n");
    EXPECT_EQ(reader.get(), "a,b\n1,2\n") << target;
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo))) << target;
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link))) << target;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);  // no temporary left
  fs::remove_all(dir);
}

TEST(AtomicWrite, ARegularFileIsReplacedWhole) {
  const fs::path dir = own_folder(), file = dir / "card.json";
  std::ofstream(file) << "old bytes, longer than the new ones";
  write_file_atomically(file.string(), "new");
  EXPECT_EQ(read_all(file), "new");
  fs::remove_all(dir);
}

// A symbolic link as the output (issue 37): the rename replaced the link by a regular file and left
// its target stale. Now the target gets the bytes (through a temporary in the target's folder),
// the link stays a link, through a chain of links and a relative link read from its own folder.
TEST(AtomicWrite, ALinkToARegularFileIsWrittenThroughAndStaysALink) {
  const fs::path dir = own_folder(), real = dir / "real", file = real / "card.json";
  const fs::path link = dir / "link.json", chain = dir / "chain.json";
  fs::create_directories(real);
  std::ofstream(file) << "old bytes";
  fs::create_symlink("real/card.json", link);  // relative: read from the link's folder
  fs::create_symlink(link, chain);
  write_file_atomically(link.string(), "new");
  EXPECT_EQ(read_all(file), "new");
  write_file_atomically(chain.string(), "newer");
  EXPECT_EQ(read_all(file), "newer");
  for (const fs::path& l : {link, chain}) EXPECT_TRUE(fs::is_symlink(fs::symlink_status(l))) << l;
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(file)));
  EXPECT_EQ(std::distance(fs::directory_iterator(real), fs::directory_iterator()), 1);  // no temporary left
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
  fs::remove_all(dir);
}

// A dangling link is written through, as the shell's `>` does: its target is made, the link kept;
// check_output_path checks the target's folder; same_file sees the link and its target as one file.
TEST(AtomicWrite, ADanglingLinkMakesItsTargetAndItsFolderIsChecked) {
  const fs::path dir = own_folder(), link = dir / "link.csv", target = dir / "made.csv";
  fs::create_symlink("made.csv", link);
  check_output_path(link.string());
  EXPECT_TRUE(same_file(link.string(), target.string()));
  write_file_atomically(link.string(), "a\n");
  EXPECT_EQ(read_all(target), "a\n");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  const fs::path lost = dir / "lost.csv";
  fs::create_symlink(dir / "no_such_folder" / "x.csv", lost);
  EXPECT_THROW(check_output_path(lost.string()), InputError);
  const fs::path loop = dir / "loop";
  fs::create_symlink("loop", loop);
  EXPECT_THROW(write_file_atomically(loop.string(), "x"), InputError);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(loop)));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fitlib::core
