#pragma once
// What `fitcli --version` prints: version, commit and the versions of the libraries it was built with.
#include <string>

namespace fitcli {

std::string version_text();

}  // namespace fitcli
