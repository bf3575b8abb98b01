#include "fitlib/fatigue/stress_csv.hpp"

#include <cmath>
#include <map>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/csv.hpp"

namespace fitlib::fatigue {

namespace {

const std::vector<std::string> kColumns = {"point", "role", "x_mm", "y_mm", "t_s",   "s11_MPa",
                                           "s22_MPa", "s12_MPa", "e11", "e22", "e12"};
constexpr std::size_t kStressColumns = 8;  // the strains are optional

}  // namespace

std::vector<PointHistory> parse_stress_histories(const std::string& text, const std::string& file) {
  std::vector<PointHistory> out;
  std::map<std::string, std::size_t> index;
  std::size_t columns = 0;  // 8, or 11 with the strains
  for (const data::CsvLine& l : data::split_csv_lines(text, file)) {
    if (data::is_blank_or_comment(l.text)) continue;
    const std::vector<std::string> f = data::split_csv_fields(l.text, file, l.number);
    if (columns == 0) {
      const std::size_t n = f.size() == kColumns.size() ? kColumns.size() : kStressColumns;
      for (std::size_t k = 0; k < n || k < f.size(); ++k)
        if (k >= f.size() || k >= n || f[k] != kColumns[k])
          throw core::InputError("expected the columns point, role, x_mm, y_mm, t_s, s11_MPa, "
                                 "s22_MPa, s12_MPa (and optionally e11, e22, e12)", file, l.number, int(k) + 1,
                                 k < n ? kColumns[k] : f[k]);
      columns = n;
      continue;
    }
    if (f.size() != columns)
      throw core::InputError("expected " + std::to_string(columns) + " fields, found " + std::to_string(f.size()),
                             file, l.number, int(f.size()) + 1);
    auto number = [&](int k) {
      return data::parse_csv_number(f[k], kColumns[k], file, l.number, k + 1);
    };
    auto strain = [&](int k) { return k < int(columns) && !f[k].empty() ? number(k) : NAN; };
    const Role role = core::material_role_from_string(f[1], "role", file, l.number, 2);
    const double x = number(2), y = number(3);
    const StressSample s{number(4), number(5), number(6), number(7), strain(8), strain(9), strain(10)};
    auto [it, added] = index.emplace(f[0], out.size());
    if (added) {  // a named point: the file does not say which FE element it came from
      PointHistory q;
      q.name = f[0], q.role = role, q.x_mm = x, q.y_mm = y;
      out.push_back(std::move(q));
    }
    PointHistory& p = out[it->second];
    if (p.role != role || p.x_mm != x || p.y_mm != y)
      throw core::InputError("point '" + f[0] + "' changes its role or position", file, l.number,
                             1, "point");
    if (!p.samples.empty() && !(s.t_s > p.samples.back().t_s))
      throw core::InputError("times of point '" + f[0] + "' must increase", file, l.number, 5, "t_s");
    p.samples.push_back(s);
  }
  if (out.empty()) throw core::InputError("no stress rows", file, 1, 0);
  return out;
}

std::vector<PointHistory> read_stress_histories(const std::string& path) {
  return parse_stress_histories(core::read_file(path), path);
}

std::string stress_histories_csv(const std::vector<PointHistory>& points) {
  std::string out = "point,role,x_mm,y_mm,t_s,s11_MPa,s22_MPa,s12_MPa,e11,e22,e12\n";
  for (const PointHistory& p : points)
    for (const StressSample& s : p.samples) {
      out += data::quote_csv_field(p.name) + "," + to_string(p.role);
      for (double v : {p.x_mm, p.y_mm, s.t_s, s.s11_MPa, s.s22_MPa, s.s12_MPa})
        out += "," + data::format_exact(v);
      for (double e : {s.e11, s.e22, s.e12}) out += "," + (std::isnan(e) ? std::string() : data::format_exact(e));
      out += "\n";
    }
  return out;
}

}  // namespace fitlib::fatigue
