// Loads a bundled card from the installed data folder and prints G' and G'' at 1 Hz.
#include <cstdio>
#include <string>

#include "fitlib/card/card.hpp"

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : FITLIB_DATA_DIR;
  const auto card = fitlib::card::load_card(data + "/datasets/cards/synthetic-prony-shear-true.json");
  fitlib::model::TestCondition c;
  c.frequency_Hz = 1.0;
  const auto values = card.values();
  const auto m = card.model()->moduli(values.data(), c);
  std::printf("%s %.6g %.6g\n", card.model_kind.c_str(), m.storage, m.loss);
  return m.storage > 0 && m.loss > 0 ? 0 : 1;
}
