// The shared vocabulary (fitlib/core/fidelity.hpp, fitlib/core/material_role.hpp): every value has
// its name and reads back, and a bad name is an InputError naming the key (and the place given).
#include <gtest/gtest.h>

#include "fitlib/core/error.hpp"
#include "fitlib/core/fidelity.hpp"
#include "fitlib/core/material_role.hpp"

namespace fitlib::core {
namespace {

TEST(Vocabulary, EveryFidelityAndRoleReadsBackFromItsName) {
  for (Fidelity f : {Fidelity::beam, Fidelity::elastic, Fidelity::complete})
    EXPECT_EQ(fidelity_from_string(to_string(f), "k"), f);
  EXPECT_STREQ(to_string(Fidelity::complete), "complete");
  for (MaterialRole r : {MaterialRole::bottom, MaterialRole::cushion})
    EXPECT_EQ(material_role_from_string(to_string(r), "k"), r);
  EXPECT_EQ(static_cast<int>(MaterialRole::bottom), 0);  // arrays by role: bottom, cushion
  EXPECT_EQ(static_cast<int>(MaterialRole::cushion), 1);
}

TEST(Vocabulary, ABadNameIsAnInputErrorAtItsKey) {
  try {
    fidelity_from_string("viscoelastic", "life.fidelity", "drive.toml", 12, 3);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "life.fidelity");
    EXPECT_EQ(e.file(), "drive.toml");
    EXPECT_EQ(e.line(), 12);
    EXPECT_EQ(e.column(), 3);
    EXPECT_NE(std::string(e.what()).find("drive.toml:12:3: key 'life.fidelity': unknown fidelity 'viscoelastic' (expected beam, "
                                              "elastic or complete)"),
              std::string::npos)
        << e.what();
  }
  try {
    material_role_from_string("cord", "role");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "role");
    EXPECT_NE(std::string(e.what()).find("unknown role 'cord' (expected bottom or cushion)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fitlib::core
