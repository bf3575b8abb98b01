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

}  // namespace
}  // namespace fitlib::core
