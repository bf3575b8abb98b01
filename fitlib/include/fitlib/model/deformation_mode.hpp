#pragma once
// The quasi-static test vocabulary (fitlib/core/deformation_mode.hpp) under the model's names.
#include "fitlib/core/deformation_mode.hpp"

namespace fitlib::model {

using core::abscissa_name;
using core::DeformationMode;
using core::deformation_mode_from_label;
using core::kDeformationModeLabels;
using core::to_string;
using core::undeformed_abscissa;

}  // namespace fitlib::model
