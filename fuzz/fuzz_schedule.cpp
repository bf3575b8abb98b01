// Staged-fit schedules (fit/staged.hpp), read from a file as `fitcli fit --schedule` reads them;
// built twice, as fuzz_schedule_json and fuzz_schedule_toml (FITLIB_FUZZ_EXTENSION picks the
// reader by the file name's extension, as load_schedule does).
#include "fitlib/fit/staged.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fitlib::fuzz::write_input(data, size, FITLIB_FUZZ_EXTENSION);
  return fitlib::fuzz::run_reader([&] {
    const auto schedule = fitlib::fit::load_schedule(path);
    for (const auto& stage : schedule.stages)
      if (stage.multistart < 0 || stage.max_iterations < 0) fitlib::fuzz::finding("accepted a negative count");
  });
}
