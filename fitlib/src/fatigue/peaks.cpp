#include "fitlib/fatigue/peaks.hpp"

#include <algorithm>

namespace fitlib::fatigue {

std::vector<Extremum> local_extrema(const std::vector<double>& v, bool periodic) {
  // Collapse plateaus into runs, then compare each run with its neighbouring runs.
  struct Run { std::size_t first; double value; };
  std::vector<Run> runs;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (runs.empty() || v[i] != runs.back().value) runs.push_back({i, v[i]});
  if (periodic && runs.size() > 1 && runs.front().value == runs.back().value) {
    runs.front().first = runs.back().first;  // the plateau wraps around the cycle's end
    runs.pop_back();
  }
  std::vector<Extremum> out;
  const std::size_t n = runs.size();
  if (n < 2) return out;
  for (std::size_t k = 0; k < n; ++k) {
    const bool has_prev = periodic || k > 0, has_next = periodic || k + 1 < n;
    if (!has_prev || !has_next) continue;
    const double prev = runs[(k + n - 1) % n].value, next = runs[(k + 1) % n].value;
    const double x = runs[k].value;
    if (x > prev && x > next) out.push_back({runs[k].first, x, true});
    else if (x < prev && x < next) out.push_back({runs[k].first, x, false});
  }
  std::sort(out.begin(), out.end(),
            [](const Extremum& a, const Extremum& b) { return a.index < b.index; });
  return out;
}

namespace {

// Steps 3–4: in each run of extrema of one kind keep the largest maximum or the smallest minimum.
std::vector<Extremum> merge_runs(std::vector<Extremum> e, bool periodic) {
  if (e.empty()) return e;
  if (periodic) {
    // Start after a minimum so that no run of maxima is cut by the cycle's end (and vice versa).
    auto start = std::find_if(e.begin(), e.end(), [&](const Extremum& x) { return !x.maximum; });
    if (start != e.end()) std::rotate(e.begin(), start + 1, e.end());
  }
  std::vector<Extremum> out;
  for (const Extremum& x : e) {
    if (!out.empty() && out.back().maximum == x.maximum) {
      const bool better = x.maximum ? x.value > out.back().value : x.value < out.back().value;
      if (better) out.back() = x;
    } else {
      out.push_back(x);
    }
  }
  if (periodic && out.size() > 1 && out.front().maximum == out.back().maximum) {
    // Only possible without minima (or without maxima): one run around the whole cycle.
    const bool back_better = out.back().maximum ? out.back().value > out.front().value
                                                : out.back().value < out.front().value;
    if (back_better) out.front() = out.back();
    out.pop_back();
  }
  std::sort(out.begin(), out.end(),
            [](const Extremum& a, const Extremum& b) { return a.index < b.index; });
  return out;
}

}  // namespace

std::vector<Extremum> significant_extrema(const std::vector<double>& values, const PeakOptions& o) {
  std::vector<Extremum> e = local_extrema(values, o.periodic);
  double largest = 0.0;
  bool any_max = false;
  for (const Extremum& x : e)
    if (x.maximum && (!any_max || x.value > largest)) largest = x.value, any_max = true;
  if (!any_max) return {};
  const double limit = o.threshold * largest;
  e.erase(std::remove_if(e.begin(), e.end(),
                         [&](const Extremum& x) { return x.maximum ? x.value < limit : x.value > limit; }),
          e.end());
  return merge_runs(std::move(e), o.periodic);
}

std::vector<Extremum> significant_peaks(const std::vector<double>& values, const PeakOptions& o) {
  std::vector<Extremum> e = significant_extrema(values, o);
  e.erase(std::remove_if(e.begin(), e.end(), [](const Extremum& x) { return !x.maximum; }), e.end());
  return e;
}

}  // namespace fitlib::fatigue
