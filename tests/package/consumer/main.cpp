// Loads a bundled card from the installed data folder and prints G' and G'' at 1 Hz, then the
// fatigue life of a bundled drive (scene::run_life: the deepest call chain, through every module
// and Ceres, glog, UMFPACK and AMD, which pkg-config --libs did not link).
#include <cstdio>
#include <string>

#include "fitlib/card/card.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : FITLIB_DATA_DIR;
  const auto card = fitlib::card::load_card(data + "/datasets/cards/synthetic-prony-shear-true.json");
  fitlib::model::TestCondition c;
  c.frequency_Hz = 1.0;
  const auto values = card.values();
  const auto m = card.model()->moduli(values.data(), c);
  const auto life = fitlib::scene::run_life(fitlib::scene::load_scene(data + "/datasets/drives/ref-0500-light.toml"));
  std::printf("%s %.6g %.6g; life %s %.4g cycles (%s)\n", card.model_kind.c_str(), m.storage, m.loss,
              life.life->report.governing.c_str(), life.life->report.life_cycles, fitlib::core::to_string(life.life->plan.fidelity));
  return m.storage > 0 && m.loss > 0 && life.life->report.life_cycles > 0 ? 0 : 1;
}
