// TEMPORARY probe (issue 35 item 3, helper h-43): placements of N terms from the smooth spectrum,
// moduli by NNLS at fixed times, figures on pyvisco's master. Removed before merge.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "../fit/fit_testing.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "fitlib/fit/terms.hpp"
#include "fitlib/model/time_series.hpp"
#include "../../../fitlib/src/fit/term_merge.hpp"

namespace fitlib {
namespace {

bool g_trace = false;
struct Fig {
  double s_rms = 0, s_max = 0, l_rms = 0, ratio = 0;
  int sc = 0;
};

Fig figs(const data::DynamicTestTable& t, const model::Model& m, const double* p, double relaxed) {
  Fig f;
  double lo = 1e300, hi = 0, s_lo = 0;
  model::TestCondition c;
  c.mode = t.rows.front().condition.mode;
  for (const auto& row : t.rows) {
    c.frequency_Hz = row.condition.frequency_Hz;
    const auto e = m.moduli(p, c);
    f.s_rms += std::pow(std::log10(e.storage / row.storage_MPa), 2);
    f.l_rms += std::pow(std::log10(e.loss / row.loss_MPa), 2);
    f.s_max = std::max(f.s_max, std::abs(e.storage / row.storage_MPa - 1));
    if (row.condition.frequency_Hz < lo) lo = row.condition.frequency_Hz, s_lo = row.storage_MPa;
    hi = std::max(hi, row.condition.frequency_Hz);
  }
  f.s_rms = std::sqrt(f.s_rms / t.rows.size());
  f.l_rms = std::sqrt(f.l_rms / t.rows.size());
  f.ratio = relaxed / s_lo;
  const int n = std::lround(20 * std::log10(hi / lo));
  double ps = 0, pv = 0;
  for (int k = 0; k <= n; ++k) {
    c.frequency_Hz = lo * std::pow(10.0, k / 20.0);
    const auto e = m.moduli(p, c);
    const double td = e.loss / e.storage;
    if (k > 0) {
      const double s = td - pv;
      if (k > 1 && s * ps < 0) { ++f.sc; if (g_trace) std::printf(" %.2f", std::log10(c.frequency_Hz)); }
      ps = s;
    }
    pv = td;
  }
  return f;
}

// tan δ of a fit at ω = 1/τ (log10 τ given)
double log10_tan_delta_at(const fit::FitResult& r, double log10_tau, model::TestMode mode) {
  model::TestCondition c;
  c.mode = mode;
  c.frequency_Hz = 1.0 / (2 * M_PI * std::pow(10.0, log10_tau));
  const auto e = r.model->moduli(r.values.data(), c);
  return std::log10(e.loss / e.storage);
}

// N positions at the quantiles of density rho over [lo, hi] (first and last at the ends).
std::vector<double> place(const std::function<double(double)>& rho, double lo, double hi, int n) {
  const int m = 2000;
  std::vector<double> cum(m + 1, 0.0);
  for (int k = 1; k <= m; ++k) {
    const double x = lo + (hi - lo) * (k - 0.5) / m;
    cum[k] = cum[k - 1] + rho(x);
  }
  std::vector<double> out;
  for (int j = 0; j < n; ++j) {
    const double target = cum[m] * j / (n - 1);
    int k = 0;
    while (k < m && cum[k + 1] < target) ++k;
    const double frac = k < m ? (target - cum[k]) / std::max(1e-300, cum[k + 1] - cum[k]) : 0.0;
    out.push_back(lo + (hi - lo) * (k + std::min(1.0, frac)) / m);
  }
  return out;
}

struct Case {
  fit::FitResult r;
  Fig f;
  double ms;
};

Case nnls_at(const data::DynamicTestTable& table, const fit::FitOptions& o, const fit::FitResult& spectrum,
             const std::vector<double>& log10_tau, const nlohmann::json& mopt) {
  const int n = log10_tau.size();
  nlohmann::json mo = mopt;
  mo["terms"] = n;
  const auto m = model::make_model("prony", mo);
  model::MaxwellSeries s;
  spectrum.model->maxwell_series(spectrum.values.data(), &s);
  std::vector<double> start(m->size(), 1.0);
  start[0] = s.relaxed;
  for (int k = 0; k < n; ++k) start[1 + n + k] = std::pow(10.0, log10_tau[k]);
  fit::FitOptions held = o;
  held.uncertainty = false;
  held.backend = fit::Backend::nnls;
  held.polish = false;
  held.fixed = {"E_inf"};
  if (m->parameters()[0].name != "E_inf") held.fixed = {m->parameters()[0].name};
  for (int k = 1; k <= n; ++k) held.fixed.push_back("tau_" + std::to_string(k));
  const auto t0 = std::chrono::steady_clock::now();
  Case c{fit::fit(m, table, held, &start), {}, 0};
  c.ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  c.f = figs(table, *c.r.model, c.r.values.data(), c.r.values[0]);
  return c;
}

void show(const char* who, int n, const Case& c) {
  std::printf("%-34s N %2d  E' %.4f max %5.1f%%  E'' %.3f  Einf %.3f  sc %2d  %.2f ms %s\n", who, n, c.f.s_rms,
              100 * c.f.s_max, c.f.l_rms, c.f.ratio, c.f.sc, c.ms,
              (c.f.s_rms < 0.0099 && c.f.s_max < 0.107 && c.f.l_rms < 0.391 && c.f.ratio > 0.85 && c.f.sc < 31) ? "BEATS" : "");
}

TEST(CompactProbe, PyviscoMasterPlacements) {
  const auto table = fit::testing::read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  const nlohmann::json mopt = {{"mode", "uniaxial"}, {"reference_C", -5.0}};
  fit::FitOptions o;
  o.residual = fit::kSpectrumResidual;
  o.storage_weight = fit::kSpectrumStorageWeight;
  fit::TermOptions t;
  t.compact.enabled = false;
  const auto sel = fit::select_terms("prony", mopt, table, o, t);
  const auto& sp = sel.result;
  const auto terms = fit::detail::positive_terms(sp);
  const double lo = terms.front().log_tau / std::log(10.0), hi = terms.back().log_tau / std::log(10.0);
  Case base{sp, figs(table, *sp.model, sp.values.data(), sp.values[0]), 0};
  show("spectrum", terms.size(), base);
  const auto mode = model::TestMode::uniaxial;
  const double ws[] = {80.0};
  for (double w : ws) {
    fit::FitOptions ow = o;
    ow.storage_weight = w;
    std::printf("--- NNLS storage weight %g\n", w);
    for (int n = 16; n <= 22; n += 1) {
      std::vector<double> ward;
      for (const auto& tm : fit::detail::merge_to(terms, n)) ward.push_back(tm.log_tau / std::log(10.0));
      show("ward", n, nnls_at(table, ow, sp, ward, mopt));
      show("even", n, nnls_at(table, ow, sp, place([](double) { return 1.0; }, lo, hi, n), mopt));
      // density ∝ |d log10 tanδ / d log10 τ| + c: dense where tan δ is steep.
      for (double c0 : {0.05, 0.15}) {
        auto rho = [&](double x) {
          const double s = (log10_tan_delta_at(sp, x + 0.05, mode) - log10_tan_delta_at(sp, x - 0.05, mode)) / 0.1;
          return std::abs(s) + c0;
        };
        char name[64];
        std::snprintf(name, sizeof name, "slope+%.2f", c0);
        show(name, n, nnls_at(table, ow, sp, place(rho, lo, hi, n), mopt));
      }
      // equal-ripple density: ρ = ln(w_s (2/π · tanδ)² + w_l)/(2K) + C, K = π²/ln 10, ∫ρ = N − 1
      for (double wr : {80.0, 600.0})
      for (double sign_cap : {0.0, 1.0, 1.25, 1.5, 2.0}) {
        std::vector<double> g;
        const int m = 400;
        for (int k = 0; k < m; ++k) {
          const double x = lo + (hi - lo) * (k + 0.5) / m;
          const double td = std::pow(10.0, log10_tan_delta_at(sp, x, mode));
          g.push_back(std::log(wr * std::pow(2.0 / M_PI * td, 2) + 1.0) / (2 * M_PI * M_PI / std::log(10.0)));
        }
        // sign-keeping density where tan δ is steep: spacing whose ripple slope 2π a(Δ)/(Δ ln10) < |s|
        std::vector<double> gs(m, 0.0);
        for (int k = 0; k < m && sign_cap > 0; ++k) {
          const double x = lo + (hi - lo) * (k + 0.5) / m;
          const double sl = std::abs(log10_tan_delta_at(sp, x + 0.05, mode) - log10_tan_delta_at(sp, x - 0.05, mode)) / 0.1;
          auto ripple_slope = [](double d) { return 2 * M_PI * 4 * std::exp(-M_PI * M_PI / std::log(10.0) / d) / (d * std::log(10.0)); };
          double da = 0.2, db = 3.0;
          for (int it = 0; it < 60; ++it) {
            const double dm = 0.5 * (da + db);
            (ripple_slope(dm) < sl ? da : db) = dm;
          }
          gs[k] = 1.0 / da <= sign_cap ? 1.0 / da : 0.0;
        }
        auto total = [&](double c) {
          double sum = 0;
          for (int k = 0; k < m; ++k) sum += std::max({0.2, g[k] + c, gs[k]});
          return sum * (hi - lo) / m;
        };
        double a = -50, b = 50;
        for (int it = 0; it < 100; ++it) {
          const double mid = 0.5 * (a + b);
          (total(mid) < n - 1 ? a : b) = mid;
        }
        const double c = 0.5 * (a + b);
        auto rho = [&](double x) {
          const int k = std::clamp(int((x - lo) / (hi - lo) * m), 0, m - 1);
          return std::max({0.2, g[k] + c, gs[k]});
        };
        char name[64];
        std::snprintf(name, sizeof name, "ripple w%g cap%g", wr, sign_cap);
        g_trace = (n == 20 && wr == 80.0 && sign_cap == 0.0);
        if (g_trace) { std::printf("sign changes at log10 f:"); }
        auto pl = place(rho, lo, hi, n);
        auto cs = nnls_at(table, ow, sp, pl, mopt);
        if (g_trace) { std::printf("\n log10 tau:"); for (int k = 0; k < n; ++k) std::printf(" %.2f(%.3g)", pl[k], cs.r.values[1 + k]); std::printf("\n tan delta slope:"); for (double x = lo; x <= hi; x += 1.0) std::printf(" %.1f:%.3f/%.3f", x, (log10_tan_delta_at(sp, x + 0.05, mode) - log10_tan_delta_at(sp, x - 0.05, mode)) / 0.1, log10_tan_delta_at(sp, x, mode)); std::printf("\n"); }
        g_trace = false;
        show(name, n, cs);
      }
      // zone rule: k terms Δz apart where |slope| keeps the sign, placed where the equal-ripple
      // weight is largest; the other terms by the equal-ripple density outside the zone.
      for (int k = 5; k <= 8; ++k) {
        const int m = 520;
        std::vector<double> xs(m), sl(m), gw(m);
        auto ripple_slope = [](double d) { return 2 * M_PI * 4 * std::exp(-M_PI * M_PI / std::log(10.0) / d) / (d * std::log(10.0)); };
        for (int j = 0; j < m; ++j) {
          xs[j] = lo + (hi - lo) * (j + 0.5) / m;
          sl[j] = std::abs(log10_tan_delta_at(sp, xs[j] + 0.05, mode) - log10_tan_delta_at(sp, xs[j] - 0.05, mode)) / 0.1;
          gw[j] = std::log(80.0 * std::pow(2.0 / M_PI * std::pow(10.0, log10_tan_delta_at(sp, xs[j], mode)), 2) + 1.0);
        }
        std::vector<double> sorted = sl;
        std::sort(sorted.begin(), sorted.end());
        const double target = 0.8 * sorted[m / 2];
        double dz = 0.3;
        while (dz + 0.05 < 3 && ripple_slope(dz + 0.05) < target) dz += 0.05;
        const double len = (k - 1) * dz;
        double best = -1, bz = 0;
        for (int j = 0; j < m; ++j) {
          const double z = xs[j];
          if (z + len > hi) break;
          double ming = 1e9, sum = 0;
          for (int i = j; i < m && xs[i] <= z + len; ++i) ming = std::min(ming, sl[i]), sum += gw[i];
          if (ripple_slope(dz) < ming && sum > best) best = sum, bz = z;
        }
        if (best < 0) { std::printf("zone k%d: none (dz %.2f)\n", k, dz); continue; }
        const int rest = n - k;
        // coarse: rest terms evenly over [lo, bz) and (bz+len, hi] in proportion to length
        const double left_len = bz - lo, right_len = hi - bz - len;
        int nl = std::lround(rest * left_len / (left_len + right_len));
        int nr = rest - nl;
        std::vector<double> pl;
        for (int i = 0; i < nl; ++i) pl.push_back(lo + left_len * i / nl);
        for (int i = 0; i < k; ++i) pl.push_back(bz + dz * i);
        for (int i = 1; i <= nr; ++i) pl.push_back(bz + len + right_len * i / nr);
        char name[64];
        std::snprintf(name, sizeof name, "zone k%d dz%.2f at %.2f", k, dz, bz);
        show(name, n, nnls_at(table, ow, sp, pl, mopt));
      }
      // density ∝ max(floor, ln tanδ + C): equal E′ ripple a(Δ)·tanδ
      for (double c0 : {0.5, 1.0}) {
        auto rho = [&](double x) { return std::max(0.3, std::log(10.0) * log10_tan_delta_at(sp, x, mode) + c0 + 3.0); };
        char name[64];
        std::snprintf(name, sizeof name, "lntan+%.1f", c0);
        show(name, n, nnls_at(table, ow, sp, place(rho, lo, hi, n), mopt));
      }
    }
  }
}

}  // namespace
}  // namespace fitlib

#include "fitlib/card/fit_card.hpp"
#include "known_truth.hpp"
namespace fitlib {
namespace {

card::FitCardOptions auto_options2() {
  card::FitCardOptions o;
  o.model = "prony";
  o.terms = "auto";
  o.model_options = {{"temperature_law", "none"}, {"reference_C", 23.0}};
  o.provenance = {"probe", "test", false};
  return o;
}

void economy_row(const char* data, const char* variant, const data::DynamicTestTable& table, card::FitCardOptions o,
                 const card::testing::Truth* truth, const std::vector<double>* f) {
  const double c0 = std::clock();
  for (int k = 0; k < 4; ++k) card::fit_card(table, o);
  const auto r = card::fit_card(table, o);
  const double ms = 1e3 * (std::clock() - c0) / CLOCKS_PER_SEC / 5.0;  // CPU, mean of 5
  model::MaxwellSeries s;
  r.result.model->maxwell_series(r.result.values.data(), &s);
  int terms = 0;
  for (double e : s.moduli) terms += e > 0;
  const Fig g = figs(table, *r.result.model, r.result.values.data(), s.relaxed);
  std::printf("| %s | %s | %d | %.4f | %.1f %% | %.3f | %.3f | %d |", data, variant, terms, g.s_rms, 100 * g.s_max, g.l_rms,
              g.ratio, g.sc);
  if (truth) {
    const auto h = card::testing::held_out(r.result, *truth, *f);
    std::printf(" %.5f / %.5f |", h.storage, h.loss);
  } else {
    std::printf(" — |");
  }
  std::printf(" %.1f |\n", ms);
}

void economy_variants(const char* data, const data::DynamicTestTable& table, card::FitCardOptions base,
                      const card::testing::Truth* truth, const std::vector<double>* f) {
  economy_row(data, "default", table, base, truth, f);
  card::FitCardOptions o = base;
  o.term.compact.equal_ripple = true;
  economy_row(data, "equal-ripple", table, o, truth, f);
  o.term.compact.tan_delta_tolerance = INFINITY;
  economy_row(data, "equal-ripple, no tan d check", table, o, truth, f);
  o.term.compact.equal_ripple = false;
  economy_row(data, "no tan d check", table, o, truth, f);
}

TEST(CompactProbe, EconomyVariants) {
  std::printf("| data | variant | terms | E' rms | max | E'' rms | Einf ratio | sign changes | held-out E'/E'' | ms |\n");
  const auto master = fit::testing::read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  card::FitCardOptions pm = auto_options2();
  pm.model_options = {{"mode", "uniaxial"}, {"reference_C", -5.0}};
  economy_variants("pyvisco master", master, pm, nullptr, nullptr);
  for (int per_decade : {20, 10})
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const double decades = 8.0 + (seed % 3);
      const auto t = card::testing::smooth_truth(static_cast<int>(decades) + 2, 1e-5 / (2.0 * M_PI), seed);
      const auto f = fit::testing::log_frequencies(1e-4, 1e-4 * std::pow(10.0, decades), per_decade * static_cast<int>(decades) + 1);
      const auto table = fit::testing::synthetic_table(*t.model, t.p, f, 0.01, 100 + seed);
      char name[64];
      std::snprintf(name, sizeof name, "truth seed %d, %.0f dec, %d/dec", int(seed), decades, per_decade);
      economy_variants(name, table, auto_options2(), &t, &f);
    }
}

}  // namespace
}  // namespace fitlib
