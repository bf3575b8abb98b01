#pragma once
// Last check before a computed table or document is written (docs/reliability.md, "finite
// outputs"): no NaN or inf may reach a file. nlohmann::json would write NaN as `null` and the
// CSV writers as `nan`; both are refused here with a NumericalError (exit 4) that names what.
#include <set>
#include <string>

#include <nlohmann/json.hpp>

namespace fitlib::core {

// Throws NumericalError "<what>: <key path> is not finite" (e.g. "life.json: damage[2].D is
// not finite") at the first non-finite number of `document`.
void require_finite_json(const nlohmann::json& document, const std::string& what);

// `csv` is a table as the writers make it: `#` comment lines, a header line of column names,
// then rows. Throws NumericalError "<what>: column '<name>', row <n> is not finite" (n counts
// data rows from 1) at the first field that reads as NaN or inf (nan, -nan, inf, -inf, +inf,
// infinity, any case).
// Columns named in `text_columns` hold labels and are not checked.
void require_finite_csv(const std::string& csv, const std::string& what,
                        const std::set<std::string>& text_columns = {});

}  // namespace fitlib::core
