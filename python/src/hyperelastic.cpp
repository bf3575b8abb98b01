// Hyperelastic fits and cards from Python (docs/hyperelastic.md): the library calls behind
// `fitcli fit --model ogden ...` on quasi-static tables and `fitcli eval --stretch`.
#include "bindings.hpp"
#include "fitlib/card/hyperelastic.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::python {

namespace {

model::DeformationMode mode_of(const std::string& text) {
  if (const auto m = model::deformation_mode_from_label(text)) return *m;
  throw core::UsageError("unknown mode '" + text + "' (" + model::kDeformationModeLabels + ")");
}

}  // namespace

void bind_hyperelastic(py::module_& m) {
  m.def(
      "fit_hyperelastic_card",
      [](const std::vector<std::string>& paths, const std::string& model, const Checked<int>& n,
         const Checked<bool>& compressible, const std::string& residual, const Checked<int>& starts,
         const Checked<std::uint64_t>& seed, const std::string& name) {
        const int terms = n.get("terms"), multistart = starts.get("multistart");
        const bool is_compressible = compressible.get("compressible");
        const std::uint64_t fit_seed = seed.get("seed");
        std::vector<data::QuasiStaticTable> tables;
        for (const auto& p : paths) tables.push_back(data::read_quasi_static_table(p));
        card::HyperelasticCardOptions o;
        o.model = model;
        o.model_options = {{"compressible", is_compressible}};
        if (terms > 0) o.model_options["terms"] = terms;
        o.fit.residual = fit::parse_stress_residual(residual);
        o.fit.multistart = multistart, o.fit.seed = fit_seed;
        o.name = name;
        const auto r = card::fit_hyperelastic_card(data::merge_quasi_static_tables(tables), o);
        return py::make_tuple(r.card, r.result.warnings);
      },
      py::arg("paths"), py::arg("model"), py::arg("terms") = 0, py::arg("compressible") = false,
      py::arg("residual") = "relative", py::arg("multistart") = 0, py::arg("seed") = 1, py::arg("name") = "",
      "fitcli fit on quasi-static tables: (card, warnings); terms 0 = the model's default");
  m.def(
      "nominal_stress",
      [](const card::Card& c, const std::string& mode, const Array& x) {
        const auto model = c.model();  // the law lives as long as its model
        const auto* law = model->hyperelastic();
        if (!law) throw core::UsageError("card '" + c.name + "' is not hyperelastic");
        const auto p = c.values();
        std::vector<double> out;
        for (double v : to_vector(x.object, "stretch")) out.push_back(law->nominal_stress(p.data(), mode_of(mode), v));
        return to_array(out);
      },
      py::arg("card"), py::arg("mode"), py::arg("stretch"),
      "Nominal stress (MPa) of a hyperelastic card in a mode at stretches (shear strains, volume ratios)");
  m.def("visco_hyperelastic_card", &card::visco_hyperelastic_card, py::arg("base"), py::arg("prony"),
        py::arg("name"), "A hyperelastic base card (long term) with the Prony series of a shear card");
}

}  // namespace fitlib::python
