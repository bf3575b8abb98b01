// Sweeps (docs/sweep.md) from Python: the table of `fitcli sweep` on threads, as its JSON
// document or CSV text.
#include "bindings.hpp"
#include "fitlib/scene/sweep_run.hpp"

namespace fitlib::python {

void bind_sweep(py::module_& m) {
  m.def(
      "sweep",
      [](const std::string& path, const Checked<int>& n, const std::string& out, const Checked<bool>& as_csv) {
        const int threads = n.get("threads");
        const bool csv = as_csv.get("csv");
        require_in("threads", threads, 1, 1024);  // fitcli sweep --threads
        const auto sweep = scene::load_sweep(path);
        scene::ThreadExecutor executor(threads);
        scene::SweepRunOptions options;
        options.out_path = out;
        options.progress = false;
        std::string table;
        {
          py::gil_scoped_release release;
          table = scene::run_sweep(sweep, executor, options).table;
        }
        return csv ? py::object(py::str(table)) : to_python(scene::sweep_json(sweep, table));
      },
      py::arg("path"), py::arg("threads") = 1, py::arg("out") = "", py::arg("csv") = false,
      "fitcli sweep on threads: the JSON document (dict) or, with csv=True, the CSV text; out: the "
      "resumable result file");
}

}  // namespace fitlib::python
