// fitcli: command-line front of fitlib (docs/cli.md).
#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "commands.hpp"
#include "fitlib/core/error.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "path_guard.hpp"
#include "plot.hpp"
#include "suggest.hpp"
#include "version_info.hpp"

namespace {

// Whether the kernel gives a transparent huge page to memory that asks for one (MADV_HUGEPAGE):
// /sys/kernel/mm/transparent_hugepage/enabled reads "always [madvise] never" or similar.
bool huge_pages_on_request() {
  std::FILE* f = std::fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!f) return false;
  char mode[64] = {};
  const bool read = std::fgets(mode, sizeof mode, f) != nullptr;
  std::fclose(f);
  return read && std::strstr(mode, "[never]") == nullptr;
}

// glibc's malloc maps every block above 128 KiB afresh and gives freed memory back to the system,
// so the fits' Jacobians and designs (0.2–0.3 MB each on pyvisco's master) fault in new pages each
// time, and a page fault costs ≈ 10 µs on the shared VM. Freed memory is kept in the heap instead,
// and its first 2 MiB are populated by one madvise call rather than by ≈ 470 faults (what `fit
// --terms auto` on pyvisco's master touches beyond start-up). Where the kernel allows, the heap's
// first 2 MiB-aligned 2 MiB are one transparent huge page, populated from the heap's top up to its
// end: one page to clear instead of 512 and fewer TLB misses in the fit (−1.2 to −2.3 ms CPU of
// `fit --terms auto`). Nothing computed differs (docs/fitting.md "Speed", docs/decisions.md
// "fitcli start-up: the Ceres stack's libraries linked statically, freed memory kept, the heap
// populated at start" and "fitcli: the heap's first 2 MiB-aligned 2 MiB as a huge page").
void keep_freed_memory() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest (HEAP_MAX_SIZE / 2 on 64-bit)
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
  constexpr std::size_t kPopulated = 2 << 20, kPage = 4096, kHuge = 2 << 20;  // bytes
  const bool huge = huge_pages_on_request();
  // From the heap's top, where it returns; with room for a whole aligned huge page.
  char* block = static_cast<char*>(std::malloc(huge ? kPopulated + kHuge : kPopulated));
  if (!block) return;
#ifdef MADV_POPULATE_WRITE  // Linux ≥ 5.14 (an older kernel refuses it: the pages fault in as before)
  const auto at = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t lo = (at + kPage - 1) & ~(kPage - 1);
  std::uintptr_t hi = (at + kPopulated) & ~(kPage - 1);
  if (huge) {
    const std::uintptr_t aligned = (at + kHuge - 1) & ~(kHuge - 1);
    madvise(reinterpret_cast<void*>(aligned), kHuge, MADV_HUGEPAGE);
    hi = aligned + kHuge;
  }
  madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_POPULATE_WRITE);
#endif
  std::free(block);
}

// fitcli's subcommands in the order `--help` lists them.
struct Subcommand {
  const char* name;
  void (*add)(CLI::App&);
};
constexpr Subcommand kSubcommands[] = {
    {"fit", fitcli::register_fit},         {"eval", fitcli::register_eval},
    {"export", fitcli::register_export},   {"synth", fitcli::register_synth},
    {"waveform", fitcli::register_waveform}, {"surface", fitcli::register_surface},
    {"belt", fitcli::register_belt},       {"accumulate", fitcli::register_accumulate},
    {"material-point", fitcli::register_material_point}, {"plot", fitcli::register_plot},
    {"segment", fitcli::register_segment}, {"life", fitcli::register_life},
    {"life-fit", fitcli::register_life_fit}, {"sweep", fitcli::register_sweep},
    {"visco-card", fitcli::register_visco_card}};

// Only the subcommand the command line names is registered (the first argument that is not an
// option: the top level has flags only), all of them otherwise (--help, --version, a misspelt
// name and its hint). CLI11's set-up of the other 14 cost `fitcli fit` about 0.6 ms of its 1 ms
// of registration (docs/fitting.md "Speed"); a subcommand parses and runs alone either way.
void register_subcommands(CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '-') continue;
    for (const Subcommand& s : kSubcommands)
      if (std::strcmp(argv[i], s.name) == 0) return s.add(app);
    break;
  }
  for (const Subcommand& s : kSubcommands) s.add(app);
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  fitcli::guard_standard_streams();
  CLI::App app{"fitcli: fit material models to dynamic tests, write cards, run belt scenes (docs/cli.md)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fitcli::version_text());
  fitcli::add_verbosity_flags(&app);
  register_subcommands(app, argc, argv);
  fitcli::require_finite_numbers(app);
  // After the whole command line is parsed, before the subcommand runs.
  app.parse_complete_callback([&app] { fitcli::refuse_colliding_paths(app); });
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "fitcli: error: " + std::string(e.what()) + " (--help lists the options)\n";
  });
  fitcli::set_command_line(argc, argv);
  try {
    fitcli::refuse_empty_list_items(argc, argv);
    app.parse(argc, argv);
    fitcli::finish_stdout();
    if (fitcli::figure_not_drawn()) return fitcli::kFigureNotDrawn;  // the other outputs stand
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    if (code != 0) {
      std::vector<std::string> names;
      for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
      if (const std::string hint = fitcli::subcommand_hint(argc, argv, names); !hint.empty())
        std::cerr << "fitcli: " << hint << "\n";
      return fitlib::core::kUsageError;
    }
    try {  // --help and --version print on stdout too
      fitcli::finish_stdout();
    } catch (const std::exception& f) {
      std::cerr << "fitcli: error: " << f.what() << "\n";
      return fitlib::core::exit_code_for(f);
    }
    return 0;
  } catch (const fitcli::FigureError& e) {  // gnuplot missing before any work, or `fitcli plot`'s only output
    std::cerr << "fitcli: error: " << e.what() << "\n";
    return fitcli::kFigureNotDrawn;
  } catch (const std::exception& e) {
    std::cerr << "fitcli: error: " << fitcli::with_stdin_named(e.what()) << "\n";
    return fitlib::core::exit_code_for(e);
  }
  return 0;
}
