// Test levels along each axis (Report V §5.2: "significant separate numerical values").
#include <algorithm>
#include <cmath>

#include "fitlib/surface/fit.hpp"

namespace fitlib::surface {
namespace {

// A level spanning more than this fraction of the axis range, or more levels than this, means the
// values do not form test levels (e.g. uniformly scattered data): the axis is "scattered", every
// distinct value is its own level, and it takes no part in the missing-cell analysis.
constexpr double kMaxLevelSpan = 0.25;
constexpr std::size_t kMaxLevels = 64;

// Single-linkage clustering of sorted values: a gap wider than `gap` starts a new level.
LevelAxis cluster(const std::vector<double>& sorted, double gap, double* widest_span) {
  LevelAxis axis;
  double sum = 0.0, lowest = sorted.front();
  std::size_t count = 0;
  *widest_span = 0.0;
  auto close_level = [&](double highest) {
    axis.centres.push_back(sum / static_cast<double>(count));
    axis.upper_bound.push_back(highest);
    *widest_span = std::max(*widest_span, highest - lowest);
  };
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (i > 0 && sorted[i] - sorted[i - 1] > gap) {
      close_level(sorted[i - 1]);
      sum = 0.0;
      count = 0;
      lowest = sorted[i];
    }
    sum += sorted[i];
    ++count;
  }
  close_level(sorted.back());
  return axis;
}

}  // namespace

std::vector<LevelAxis> find_levels(const SampleSet& data, const std::vector<Transform>& transforms,
                                   double level_tolerance) {
  std::vector<LevelAxis> levels;
  for (Eigen::Index k = 0; k < data.x.cols(); ++k) {
    std::vector<double> sorted(static_cast<std::size_t>(data.x.rows()));
    for (Eigen::Index r = 0; r < data.x.rows(); ++r) {
      const double x = data.x(r, k);
      sorted[static_cast<std::size_t>(r)] =
          transforms[static_cast<std::size_t>(k)] == Transform::log10 ? std::log10(x) : x;
    }
    std::sort(sorted.begin(), sorted.end());
    const double range = sorted.back() - sorted.front();
    double widest = 0.0;
    LevelAxis axis = cluster(sorted, level_tolerance * range, &widest);
    const bool wide_level = range > 0.0 && widest > kMaxLevelSpan * range;
    if (wide_level) axis = cluster(sorted, 0.0, &widest);
    axis.scattered = wide_level || axis.centres.size() > kMaxLevels;
    levels.push_back(std::move(axis));
  }
  return levels;
}

}  // namespace fitlib::surface
