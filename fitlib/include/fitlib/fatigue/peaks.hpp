#pragma once
// The four-step peak extraction of Report I §6.4 (docs/fatigue.md §2) on the
// effective-stress history of one load cycle.
#include <cstddef>
#include <vector>

namespace fitlib::fatigue {

struct PeakOptions {
  double threshold = 0.25;  // step 2: share of the largest maximum
  // The samples are one period of a steady cycle: the last sample is followed by the first, so
  // the cycle's start is not an extremum of its own (docs/decisions.md "fatigue: peaks on a
  // periodic cycle"). Off: the first and last samples are never extrema.
  bool periodic = true;
};

struct Extremum {
  std::size_t index = 0;  // sample index (the first of a plateau)
  double value = 0.0;
  bool maximum = true;
};

// Step 1: every strict local maximum and minimum; a plateau counts once.
std::vector<Extremum> local_extrema(const std::vector<double>& values, bool periodic);

// Steps 1–4: the significant extrema in time order. The maxima are the peaks σ_emax,i of (6.31).
std::vector<Extremum> significant_extrema(const std::vector<double>& values,
                                          const PeakOptions& options = {});

// Only the maxima of significant_extrema.
std::vector<Extremum> significant_peaks(const std::vector<double>& values,
                                        const PeakOptions& options = {});

}  // namespace fitlib::fatigue
