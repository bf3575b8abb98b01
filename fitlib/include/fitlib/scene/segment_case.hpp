#pragma once
// The scene's static segment case ([segment]) for `fitcli segment`: runs it, optionally writes
// the deformed mesh with cell stresses (VTK), and reports it as JSON.
#include <string>

#include <nlohmann/json.hpp>

#include "fitlib/scene/scene.hpp"

namespace fitlib::scene {

segment::StaticResult run_segment_case(const Scene& scene, const std::string& vtk_path = {});
nlohmann::json segment_json(const Scene& scene, const segment::StaticResult& result);

}  // namespace fitlib::scene
