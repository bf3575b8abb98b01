#pragma once
// The scene's static segment case ([segment]) for `fitcli segment`: runs it, optionally writes
// the deformed mesh with cell stresses (VTK), and reports it as JSON.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/scene/scene.hpp"

namespace fitlib::scene {

// Where a role's material came from: a [belt.materials] card's elastic equivalent at the scene's
// temperature and the case's load frequency, or the [segment.materials] E and nu under [segment] law.
struct SegmentMaterial {
  std::string role, source;  // source: the card's path, or "[segment.materials]"
  std::string material;      // the material point's own description, or "E … MPa, nu …"
};

struct SegmentCase {
  segment::StaticResult result;
  std::vector<SegmentMaterial> materials;  // bottom, cushion
  double temperature_C = 0.0, frequency_Hz = 0.0;  // where the cards were read (frequency 0: no card)
  std::vector<std::string> warnings;       // cards read beyond their data windows
};

// The roles with a [belt.materials] card take its elastic equivalent (segment::role_point at the
// elastic fidelity), the others [segment.materials]; a card needs a load frequency: [segment]
// frequency_Hz, else the drive's (InputError at segment.frequency_Hz when the scene has neither).
// A `vtk_path` is checked writable (core::check_output_path) before the FE runs and written
// through a temporary and a rename; callers refuse one that is an input
// (scene::refuse_outputs_on_inputs, under their own name for it).
SegmentCase run_segment_case(const Scene& scene, const std::string& vtk_path = {});
nlohmann::json segment_json(const Scene& scene, const SegmentCase& c);

}  // namespace fitlib::scene
