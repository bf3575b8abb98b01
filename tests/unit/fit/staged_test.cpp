// Staged schedules: parsing (JSON and TOML), selectors, errors naming the key, and a staged fit.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include "fit_testing.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/staged.hpp"

using namespace fitlib;
using namespace fitlib::fit::testing;

namespace {

const char* kJson = R"({"stages": [
  {"name": "moduli", "free": ["group:elastic", "group:viscous"], "backend": "nnls"},
  {"name": "times", "free": ["*"], "lock": ["group:elastic", "group:viscous"], "backend": "nlopt", "multistart": 3},
  {"name": "finish", "free": ["*"], "lock": ["G_inf"], "backend": "ceres", "max_iterations": 200}]})";

const char* kToml = R"(
[[stages]]
name = "moduli"
free = ["group:elastic", "group:viscous"]
backend = "nnls"

[[stages]]
name = "times"
free = ["*"]
lock = ["group:elastic", "group:viscous"]
backend = "nlopt"
multistart = 3

[[stages]]
name = "finish"
free = ["*"]
lock = ["G_inf"]
backend = "ceres"
max_iterations = 200
)";

std::string temp_file(const std::string& name, const std::string& content) {
  const std::string path = fitlib_test::temp_path(name);
  core::write_file_atomically(path, content);
  return path;
}

}  // namespace

TEST(Staged, JsonAndTomlReadTheSameSchedule) {
  const auto a = fit::load_schedule(temp_file("fit_schedule.json", kJson));
  const auto b = fit::load_schedule(temp_file("fit_schedule.toml", kToml));
  ASSERT_EQ(a.stages.size(), 3u);
  ASSERT_EQ(b.stages.size(), 3u);
  for (int s = 0; s < 3; ++s) {
    EXPECT_EQ(a.stages[s].name, b.stages[s].name);
    EXPECT_EQ(a.stages[s].free, b.stages[s].free);
    EXPECT_EQ(a.stages[s].lock, b.stages[s].lock);
    EXPECT_EQ(a.stages[s].backend, b.stages[s].backend);
    EXPECT_EQ(a.stages[s].multistart, b.stages[s].multistart);
    EXPECT_EQ(a.stages[s].max_iterations, b.stages[s].max_iterations);
  }
}

TEST(Staged, ErrorsNameTheKey) {
  try {
    fit::parse_schedule_json(R"({"stages": [{"free": ["*"], "backnd": "ceres"}]})");
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), "stages[0].backnd");
  }
  EXPECT_THROW(fit::parse_schedule_json(R"({"stages": []})"), core::InputError);
  EXPECT_THROW(fit::parse_schedule_json(R"({"stages": [{"backend": "lbfgs"}]})"), core::InputError);
  const auto model = prony(2);
  try {
    fit::select_parameters(model->parameters(), {"tau_*", "group:damage"}, "stages[1].free");
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), "stages[1].free[1]");
  }
}

TEST(Staged, Selectors) {
  const auto model = prony(2);  // G_inf, G_1, G_2, tau_1, tau_2
  const auto& s = model->parameters();
  EXPECT_EQ(fit::select_parameters(s, {"*"}, "k").size(), 5u);
  EXPECT_EQ(fit::select_parameters(s, {"tau_*"}, "k"), (std::vector<int>{3, 4}));
  EXPECT_EQ(fit::select_parameters(s, {"G_inf", "tau_2"}, "k"), (std::vector<int>{0, 4}));
  EXPECT_EQ(fit::select_parameters(s, {"group:viscous"}, "k"), (std::vector<int>{1, 2}));
}

TEST(Staged, ScheduleFileAndDefaultScheduleRecoverTheTruth) {
  const auto model = prony(2);
  const auto truth = prony_parameters(1.0, {4.0, 2.0}, {0.01, 10.0});
  const auto table = synthetic_table(*model, truth, log_frequencies(1e-3, 1e3, 30), 0.0, 31);
  fit::FitOptions o;
  o.backend = fit::Backend::staged;
  o.multistart = 4;
  const auto by_default = fit::fit(model, table, o);
  o.schedule_path = temp_file("fit_schedule2.toml", kToml);
  const auto by_file = fit::fit(model, table, o);
  EXPECT_EQ(by_file.backend_used, "staged");
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_NEAR(by_default.values[i], truth[i], 1e-4 * truth[i]) << i;
    if (i > 0) {
      EXPECT_NEAR(by_file.values[i], truth[i], 0.1 * truth[i]) << i;
    }
  }
  int stages = 0;
  for (const auto& m : by_file.messages) stages += m.rfind("stage '", 0) == 0;
  EXPECT_EQ(stages, 3);
  // G_inf was locked in the last stage (held at its NNLS value): not part of the covariance.
  EXPECT_FALSE(by_file.parameters[0].std_error);
  EXPECT_NE(by_file.parameters[0].reason.find("final stage"), std::string::npos);
}
