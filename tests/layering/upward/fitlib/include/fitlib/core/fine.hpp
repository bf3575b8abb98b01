#pragma once
// A fixture of the layering test: an include within the module is allowed.
#include "fitlib/core/error.hpp"
