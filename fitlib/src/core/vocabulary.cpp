// The shared vocabulary's names (fitlib/core/fidelity.hpp, fitlib/core/material_role.hpp): one
// table per enum, both ways.
#include "fitlib/core/enum_names.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/fidelity.hpp"
#include "fitlib/core/material_role.hpp"

namespace fitlib::core {
namespace {

constexpr EnumName<Fidelity> kFidelityNames[] = {
    {Fidelity::beam, "beam"}, {Fidelity::elastic, "elastic"}, {Fidelity::complete, "complete"}};
constexpr EnumName<MaterialRole> kRoleNames[] = {{MaterialRole::bottom, "bottom"}, {MaterialRole::cushion, "cushion"}};

// parse_enum's value, or its error as an InputError at the key: "unknown <name> '<text>' (expected
// a, b or c)", <name> the key's last part.
template <class E, std::size_t N>
E parse_at(const EnumName<E> (&names)[N], const std::string& text, const std::string& key, const std::string& file,
           int line, int column) {
  try {
    return parse_enum(names, text, key.substr(key.rfind('.') + 1));
  } catch (const UsageError& e) {
    throw InputError(e.what(), file, line, column, key);
  }
}

}  // namespace

const char* to_string(Fidelity fidelity) { return enum_name(kFidelityNames, fidelity); }

Fidelity fidelity_from_string(const std::string& text, const std::string& key, const std::string& file, int line,
                              int column) {
  return parse_at(kFidelityNames, text, key, file, line, column);
}

const char* to_string(MaterialRole role) { return enum_name(kRoleNames, role); }

MaterialRole material_role_from_string(const std::string& text, const std::string& key, const std::string& file,
                                       int line, int column) {
  return parse_at(kRoleNames, text, key, file, line, column);
}

}  // namespace fitlib::core
