// Belt scenes (formats.md §5, TOML), read from a file as `fitcli belt --scene` reads them.
#include "fitlib/scene/scene.hpp"
#include "fuzz_common.hpp"

using fitlib::fuzz::require_finite;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fitlib::fuzz::write_input(data, size, ".toml");
  return fitlib::fuzz::run_reader([&] {
    const auto scene = fitlib::scene::load_scene(path);
    for (const auto& p : scene.pulleys) {
      require_finite(p.pitch_diameter_mm, "pitch diameter");
      require_finite(p.torque_Nm, "pulley torque");
      if (p.speed_rpm) require_finite(*p.speed_rpm, "pulley speed");
      if (p.center_mm) require_finite(p.center_mm->first, "pulley centre x");
      if (p.center_mm) require_finite(p.center_mm->second, "pulley centre y");
    }
    if (scene.center_distance_mm) require_finite(*scene.center_distance_mm, "centre distance");
    if (scene.torque_Nm) require_finite(*scene.torque_Nm, "torque");
    if (scene.power_kW) require_finite(*scene.power_kW, "power");
    require_finite(scene.tension_N, "tension");
    require_finite(scene.temperature_C, "temperature");
    require_finite(scene.friction, "friction");
    const auto& b = scene.belt;
    for (double v : {b.height_mm, b.width_mm, b.area_mm2, b.density_kg_m3, b.wedge_half_angle_rad,
                     b.c_N, b.k1_MPa, b.EI_Nmm2, scene.cord_area_mm2, scene.bending_inertia_mm4})
      require_finite(v, "belt property");
    for (const auto& [name, v] : scene.extra_geometry_mm) require_finite(v, "belt geometry " + name);
    if (scene.accumulation) {
      require_finite(scene.accumulation->shear_stress_MPa, "accumulation shear stress");
      if (scene.accumulation->kappa) require_finite(*scene.accumulation->kappa, "kappa");
      if (scene.accumulation->strain_limit) require_finite(*scene.accumulation->strain_limit, "strain limit");
    }
    if (scene.cvt) {
      const auto& c = *scene.cvt;
      for (double v : {c.tight_tension_N, c.slack_tension_N, c.groove_half_angle_deg, c.driver_wrap_rad,
                       c.driven_wrap_rad})
        require_finite(v, "cvt value");
    }
    if (scene.tension_test && scene.tension_test->S_N) require_finite(*scene.tension_test->S_N, "S_N");
  });
}
