// Material cards (formats.md §3), read from a file as `fitcli eval/export --card` read them.
#include "fitlib/card/card.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fitlib::fuzz::write_input(data, size, ".json");
  return fitlib::fuzz::run_reader([&] {
    const auto card = fitlib::card::load_card(path);
    for (const auto& p : card.parameters) {
      fitlib::fuzz::require_finite(p.value, "card parameter value");
      if (p.std_error) fitlib::fuzz::require_finite(*p.std_error, "card std_error");
      if (p.ci95_low) fitlib::fuzz::require_finite(*p.ci95_low, "card ci95 bound");
      if (p.ci95_high) fitlib::fuzz::require_finite(*p.ci95_high, "card ci95 bound");
    }
    card.model();  // the card names a model the registry can build
  });
}
