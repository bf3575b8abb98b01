// Staged-fit schedules in JSON (fit/staged.hpp), read from a file as `fitcli fit --schedule` reads them.
#include "fitlib/fit/staged.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fitlib::fuzz::write_input(data, size, ".json");
  return fitlib::fuzz::run_reader([&] {
    const auto schedule = fitlib::fit::load_schedule(path);
    for (const auto& stage : schedule.stages)
      if (stage.multistart < 0 || stage.max_iterations < 0) fitlib::fuzz::finding("accepted a negative count");
  });
}
