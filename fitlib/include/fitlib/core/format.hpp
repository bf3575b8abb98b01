#pragma once
// The one number formatter of every text output (docs/decisions.md, "core: one number
// formatter"): std::to_chars, so the text never depends on the locale.
#include <string>

namespace fitlib::core {

// The shortest decimal text that reads back (strtod, from_chars) as the same double: fixed or
// scientific, whichever is shorter ("0.1", "2000", "1e+06", "1.2345678901234567e-05");
// "nan", "inf", "-inf" for the non-finite values.
std::string format_number(double value);

// At most `max_significant` (1 … 17) significant digits, as printf's %.<max_significant>g in the
// C locale (trailing zeros dropped), for solver decks with field limits: the text has at most
// max_significant + 7 characters ("-d.ddde-308").
std::string format_number(double value, int max_significant);

}  // namespace fitlib::core
