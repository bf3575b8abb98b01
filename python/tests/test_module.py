#!/usr/bin/env python3
"""Tests of the Python module (plain script, run by ctest as `python_module`).

Environment: PYTHONPATH = <build>/python, FITCLI = the fitcli binary, FITLIB_ROOT = the source
tree. Each test is a function test_*; the last line is 'N passed, M failed' and the exit code is
0 only when none failed. Files go to a per-process folder under the system's temporary folder.
"""
import atexit
import csv
import io
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import traceback

import numpy as np

import fitlib

ROOT = os.environ["FITLIB_ROOT"]
FITCLI = os.environ["FITCLI"]
WORK = os.path.join(tempfile.gettempdir(), f"fitlib-python-{os.getpid()}")
os.makedirs(WORK, exist_ok=True)
if not os.environ.get("FITLIB_KEEP_TEST_FILES"):  # as the C++ tests' folder (tests/common/temp_path.hpp)
    atexit.register(shutil.rmtree, WORK, ignore_errors=True)


def source(*parts):
    return os.path.join(ROOT, *parts)


def work(name):
    return os.path.join(WORK, name)


def fitcli(*args):
    run = subprocess.run([FITCLI, *map(str, args)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return run.stdout


def without_command(document):
    document = json.loads(json.dumps(document))
    document["provenance"].pop("command")
    return document


def expect(error_class, call):
    try:
        call()
    except error_class as e:
        return e
    raise AssertionError(f"expected {error_class.__name__}")


MASTER = source("datasets", "materials", "pyvisco-freq-master.csv")
SHEAR = source("datasets", "materials", "synthetic-prony-shear.csv")


# ---- fit: the module gives the CLI's card -------------------------------------------------------
def test_fit_terms_auto_reproduces_the_cli_card():
    fitcli("fit", "--data", MASTER, "--format", "pyvisco", "--model", "prony", "--terms", "auto",
           "--out", work("cli-auto.json"))
    card, result, selection = fitlib.fit_card(MASTER, "prony", "auto", format="pyvisco")
    cli = json.load(open(work("cli-auto.json")))
    assert without_command(card.to_json()) == without_command(cli)
    assert [p["value"] for p in cli["parameters"]] == list(card.values())
    assert selection.chosen == len(card.values()) // 2 and selection.method == "spectrum"
    assert result.metrics.n_points == 206


def test_fit_fixed_terms_native_shear_reproduces_the_cli_card():
    fitcli("fit", "--data", SHEAR, "--model", "prony", "--terms", "3", "--out", work("cli-3.json"))
    card, result, _ = fitlib.fit_card(SHEAR, "prony", 3)
    assert without_command(card.to_json()) == without_command(json.load(open(work("cli-3.json"))))
    names = [p.name for p in result.parameters]
    assert names == ["G_inf", "G_1", "G_2", "G_3", "tau_1", "tau_2", "tau_3"], names
    assert result.identifiability.rank > 0 and isinstance(result.quality.acceptable, bool)


def test_fit_result_carries_intervals_metrics_and_verdict():
    table = fitlib.read_table(SHEAR)
    model = fitlib.make_model("prony", {"terms": 2, "mode": "shear"})
    result = fitlib.fit(model, table, fitlib.FitOptions(backend="ceres"))
    assert result.backend_used == "ceres"
    for p in result.parameters:
        if p.std_error is not None:
            assert p.ci95_low < p.value < p.ci95_high
    assert result.metrics.converged and result.metrics.n_free == model.size
    assert {f.modulus for f in result.quality.figures} >= {"storage", "loss"}


# ---- tables -------------------------------------------------------------------------------------
def test_table_columns_are_the_file_numbers():
    raw = np.genfromtxt(MASTER, delimiter=",", skip_header=2)
    table = fitlib.read_table(MASTER, format="pyvisco")
    assert len(table) == raw.shape[0]
    assert np.array_equal(table.frequency_Hz, raw[:, 0])
    assert np.array_equal(table.storage_MPa, raw[:, 1]) and np.array_equal(table.loss_MPa, raw[:, 2])
    assert set(table.mode) == {"uniaxial"}
    again = fitlib.parse_table(table.to_csv(), "copy.csv")
    assert np.array_equal(again.storage_MPa, table.storage_MPa)


def test_eplexor_table_is_read_by_content():
    table = fitlib.read_table(source("datasets", "materials", "pyvisco-eplexor-master.xls"), format="pyvisco")
    assert len(table) > 10 and np.all(table.storage_MPa > 0)


# ---- models -------------------------------------------------------------------------------------
def test_prony_moduli_match_the_closed_form_and_broadcast():
    model = fitlib.make_model("prony", {"terms": 1, "mode": "shear"})
    G_inf, G_1, tau = 2.0, 5.0, 0.1
    f = np.logspace(-2, 3, 7)
    out = model.moduli([G_inf, G_1, tau], f)
    wt = 2 * np.pi * f * tau
    assert np.allclose(out["storage_MPa"], G_inf + G_1 * wt**2 / (1 + wt**2), rtol=1e-14)
    assert np.allclose(out["loss_MPa"], G_1 * wt / (1 + wt**2), rtol=1e-14)
    grid = model.moduli([G_inf, G_1, tau], f[:, None], temperature_C=np.array([23.0, 23.0]))
    assert grid["storage_MPa"].shape == (7, 2)
    t = np.array([0.0, 0.1, 1.0])
    assert np.allclose(model.relaxation_modulus([G_inf, G_1, tau], t), G_inf + G_1 * np.exp(-t / tau), rtol=1e-12)
    # Standard linear solid: J(t) = 1/G_inf − (1/G_inf − 1/G_0) exp(−t/τ_c), τ_c = τ G_0/G_inf.
    G_0, tau_c = G_inf + G_1, tau * (G_inf + G_1) / G_inf
    J = 1 / G_inf - (1 / G_inf - 1 / G_0) * np.exp(-t / tau_c)
    assert np.allclose(model.creep_compliance([G_inf, G_1, tau], t), J, rtol=1e-5)  # J(t) is computed numerically


# ---- cards --------------------------------------------------------------------------------------
def test_card_round_trip_and_eval_equal_the_cli():
    card, _, _ = fitlib.fit_card(SHEAR, "prony", 3, out=work("py-3.json"))
    assert open(work("py-3.json")).read() == card.to_json_text()
    loaded = fitlib.load_card(work("py-3.json"))
    assert loaded.to_json() == card.to_json()
    assert loaded.parameter_names == [p["name"] for p in card.to_json()["parameters"]]
    assert fitlib.card_from_json(card.to_json()).to_json_text() == card.to_json_text()
    f = [0.01, 1.0, 100.0]
    rows = list(csv.DictReader(io.StringIO(fitcli("eval", "--card", work("py-3.json"), "--mode", "shear",
                                                  "--frequency-hz", ",".join(map(repr, f))))))
    mine = loaded.eval(f, mode="shear")
    assert [float(r["storage_MPa"]) for r in rows] == list(mine["storage_MPa"])
    assert [float(r["loss_MPa"]) for r in rows] == list(mine["loss_MPa"])


def test_card_export_equals_the_cli():
    card = fitlib.load_card(source("datasets", "cards", "synthetic-prony-shear-true.json"))
    path = source("datasets", "cards", "synthetic-prony-shear-true.json")
    assert card.export("abaqus") == fitcli("export", "--card", path, "--format", "abaqus")
    wlf = source("datasets", "cards", "synthetic-prony-wlf-true.json")
    at60 = fitlib.load_card(wlf).export("ansys", temperature_C=60.0)
    assert at60 == fitcli("export", "--card", wlf, "--format", "ansys", "--temperature-c", "60")
    assert "TB,SHIFT" not in at60 and "at 60 degC only" in at60


# ---- errors -------------------------------------------------------------------------------------
def test_bad_table_is_an_input_error_naming_file_and_line():
    path = source("tests", "data", "malformed", "non_number.csv")
    e = expect(fitlib.InputError, lambda: fitlib.read_table(path))
    assert e.file == path and e.line > 1 and e.column > 0, (e.file, e.line, e.column)
    assert str(e).startswith(path) and e.exit_code == 3 and isinstance(e, fitlib.FitlibError)


def test_missing_file_is_an_input_error_naming_it():
    e = expect(fitlib.InputError, lambda: fitlib.load_card(work("no-such-card.json")))
    assert e.file.endswith("no-such-card.json"), e.file


def test_bad_card_key_is_an_input_error_naming_the_key():
    document = fitlib.load_card(source("datasets", "cards", "synthetic-prony-shear-true.json")).to_json()
    document["parameters"][1]["value"] = "three"
    with open(work("bad-card.json"), "w") as f:
        json.dump(document, f)
    e = expect(fitlib.InputError, lambda: fitlib.load_card(work("bad-card.json")))
    assert e.file.endswith("bad-card.json") and e.key, (e.file, e.key, str(e))


def test_usage_and_numerical_errors_are_their_own_classes():
    expect(fitlib.UsageError, lambda: fitlib.make_model("prony", {"terms": 1}).moduli([1, 1, 1], [1.0, -2.0]))
    e = expect(fitlib.UsageError, lambda: fitlib.make_model("no-such-model"))
    assert e.exit_code == 2 and not isinstance(e, fitlib.InputError)
    prony = fitlib.make_model("prony", {"terms": 1, "mode": "shear"})
    e = expect(fitlib.NumericalError, lambda: prony.creep_compliance([0.0, 0.0, 1.0], [1.0]))  # no glassy modulus
    assert e.exit_code == 4 and isinstance(e, fitlib.FitlibError) and "glassy modulus" in str(e)


def test_surface_outside_its_interval_is_an_input_error():
    x = np.array([[a, b] for a in (0.0, 0.5, 1.0) for b in (1.0, 2.0, 3.0)])
    y = 1 + 2 * x[:, 0] + 3 * x[:, 0] ** 2 - x[:, 1] + 0.5 * x[:, 0] * x[:, 1]
    s = fitlib.fit_surface(x, y, ["a", "b"])
    expect(fitlib.InputError, lambda: s([2.0, 1.0]))
    expect(fitlib.UsageError, lambda: s([0.5, 1.0, 2.0]))  # three coordinates for two axes


# ---- surfaces, points, scenes -------------------------------------------------------------------
def test_surface_reproduces_a_polynomial_of_its_degree():
    x = np.array([[a, b] for a in (0.0, 0.5, 1.0) for b in (1.0, 2.0, 3.0)])
    law = lambda p: 1 + 2 * p[:, 0] + 3 * p[:, 0] ** 2 - p[:, 1] + 0.5 * p[:, 0] * p[:, 1]
    s = fitlib.fit_surface(x, law(x), ["a", {"name": "b", "transform": "linear"}])
    q = np.array([[0.1, 1.3], [0.77, 2.9], [0.5, 2.5]])
    assert np.allclose(s(q), law(q), atol=1e-12)
    s.save(work("s.json"))
    assert np.array_equal(fitlib.load_surface(work("s.json"))(q), s(q))
    # log10 of y: the same polynomial as the exponent of 10, reproduced as y; a zero y is refused
    g = fitlib.fit_surface(x, 10.0 ** law(x), ["a", "b"], dependent_transform="log10")
    assert g.dependent_transform == "log10"
    assert np.allclose(g(q), 10.0 ** law(q), rtol=1e-10)
    expect(fitlib.InputError, lambda: fitlib.fit_surface(x, law(x) * 0.0, ["a", "b"], dependent_transform="log10"))


def test_elastic_point_stiffness_is_the_storage_modulus():
    card = fitlib.load_card(source("datasets", "cards", "synthetic-prony-shear-true.json"))
    point = fitlib.make_material_point(card.model(), card.values(), fidelity="elastic", frequency_Hz=2.0,
                                       bulk_modulus_MPa=2000.0)
    storage = card.eval([2.0], mode="shear")["storage_MPa"][0]
    strain = np.zeros(6)
    strain[5] = 1e-3
    stress, _, tangent = point.update(point.initial_state(), strain, 0.1)
    assert math.isclose(stress[5], storage * 1e-3, rel_tol=1e-10) and math.isclose(tangent[5, 5], storage, rel_tol=1e-10)
    run = fitlib.drive_test(point, mode="shear", amplitude=0.01, cycles=1, steps_per_cycle=40)
    assert np.allclose(run["test_stress_MPa"], storage * run["test_strain"], rtol=1e-9, atol=1e-12)
    t = np.linspace(0.0, 1.0, 11)
    free = fitlib.drive(point, t, [None] * 5 + [["strain", 0.002 * t]])  # γ12 imposed, σ = 0 elsewhere
    assert np.allclose(free["stress_MPa"][:, 5], storage * 0.002 * t, rtol=1e-9, atol=1e-12)
    assert np.abs(free["stress_MPa"][:, :5]).max() < 1e-9 and free["strain"].shape == (11, 6)


def test_material_point_refuses_non_finite_input_instead_of_answering_nan():
    card = fitlib.load_card(source("datasets", "cards", "material-2-true.json"))
    point = fitlib.make_material_point(card.model(), card.values(), frequency_Hz=55.0, temperature_C=80.0)
    state, strain, nan, inf = point.initial_state(), np.full(6, 1e-3), float("nan"), float("inf")
    assert np.all(np.isfinite(point.update(state, strain, 1e-3, nan)[0]))  # NaN temperature = the reference
    for bad_strain in (np.full(6, nan), np.array([1e-3, inf, 0, 0, 0, 0])):
        assert "strain is not finite" in str(expect(fitlib.UsageError, lambda: point.update(state, bad_strain, 1e-3)))
    assert "state is not finite" in str(expect(fitlib.UsageError, lambda: point.update(np.full(point.state_size, nan), strain, 1e-3)))
    assert "temperature" in str(expect(fitlib.UsageError, lambda: point.update(state, strain, 1e-3, inf)))
    for f in (nan, -5.0, 0.0, inf):
        expect(fitlib.UsageError, lambda: point.complex_stiffness(f))
    expect(fitlib.UsageError, lambda: point.complex_stiffness(1.0, -inf))
    expect(fitlib.UsageError, lambda: fitlib.make_material_point(card.model(), card.values(), "elastic", inf, 80.0))
    expect(fitlib.UsageError, lambda: fitlib.make_material_point(card.model(), card.values(), "elastic", 1.0, inf))
    e = expect(fitlib.UsageError, lambda: fitlib.drive(point, [0, 0.5, 1], [["strain", [0, nan, 0.02]]] + [None] * 5))
    assert "component 1 is not finite at sample 1" in str(e)  # was "stress-controlled components did not converge"
    expect(fitlib.UsageError, lambda: fitlib.drive_test(point, amplitude=nan, cycles=1, steps_per_cycle=20))
    expect(fitlib.UsageError, lambda: fitlib.drive(point, [0, 1], [["strain", [0, 0.01]]] + [None] * 5, temperature_C=[80, inf]))
    values = list(card.values())
    values[0] = nan
    assert "is not finite" in str(expect(fitlib.UsageError, lambda: fitlib.make_material_point(card.model(), values)))
    assert "is not finite" in str(expect(fitlib.UsageError, lambda: card.model().moduli(values, [1.0])))


def test_material_point_holds_damage_at_the_drivers_a_test_reached():
    card = fitlib.load_card(source("datasets", "cards", "material-2-true.json"))
    model = card.model()
    held = model.damage_drivers(card.values(), "shear", "12", 0.045)  # γ/√2, where the complete level holds it
    assert np.allclose(held, [0.045 / np.sqrt(2.0)], rtol=1e-14)
    assert len(fitlib.make_model("elastic-iso").damage_drivers([10.0, 0.3], "shear", "12", 0.045)) == 0
    law = fitlib.make_material_point(model, card.values())
    hold = fitlib.make_material_point(model, card.values(), damage_driver_hold=held)
    def peak(point, gamma):  # peak shear stress of 3 cycles of simple shear at 10 Hz
        t = np.linspace(0.0, 0.3, 121)
        shear = [["strain", np.zeros_like(t)]] * 5 + [["strain", gamma * np.sin(20 * np.pi * t)]]
        return np.max(np.abs(fitlib.drive(point, t, shear)["stress_MPa"][:, 5]))
    assert peak(hold, 0.04) == peak(law, 0.04)  # driver 0.028 below the hold: the law
    assert abs(peak(hold, 0.4) / peak(hold, 0.2) - 2.0) < 0.02  # beyond it: no more damage
    assert peak(law, 0.4) / peak(law, 0.2) < 1.9
    expect(fitlib.UsageError, lambda: fitlib.make_material_point(model, card.values(), damage_driver_hold=[0.03, 0.03]))


def test_scene_load_cycle_equals_the_cli_load_history():
    path = source("datasets", "drives", "ref-0500-heavy.toml")
    fitcli("belt", "--scene", path, "--out", work("belt"))
    with open(work("belt/load_history.csv")) as f:
        rows = list(csv.DictReader(f))
    scene = fitlib.load_scene(path)
    result = scene.run()
    cycle = result.load_cycle
    assert len(cycle["s_mm"]) == len(rows)
    assert np.allclose(cycle["F_N"], [float(r["F_N"]) for r in rows], rtol=1e-9)
    assert list(cycle["zone"]) == [r["zone"] for r in rows]
    summary = fitlib.scene_summary(scene, result)
    cli = json.load(open(work("belt/summary.json")))
    assert summary["load_cycle"]["pulleys"] == cli["load_cycle"]["pulleys"]


def test_sweep_equals_fitcli_sweep():
    path = source("tests", "data", "sweep", "small.toml")
    cli = fitcli("sweep", "--sweep", path, "--quiet")
    assert fitlib.sweep(path, threads=2, csv=True) == cli
    table = fitlib.sweep(path)
    assert table == json.loads(fitcli("sweep", "--sweep", path, "--json", "--quiet"))
    assert len(table["rows"]) == 24 and table["rows"][2]["status"] == "input_error"


def test_scene_error_names_file_and_key():
    with open(source("datasets", "drives", "ref-0500-heavy.toml")) as f:
        text = f.read().replace("[conditions]", "[conditions]\nno_such_key = 1", 1)
    e = expect(fitlib.InputError, lambda: fitlib.parse_scene(text, "my-scene.toml"))
    assert e.file == "my-scene.toml" and "no_such_key" in (e.key + str(e)), (e.file, e.key, str(e))


# ---- master curves, shift files, relaxation data (fit/master_curve.hpp, fit/shift_laws.hpp) ----
RAW = source("datasets", "materials", "pyvisco-freq-raw.csv")
TIME_MASTER = source("datasets", "materials", "pyvisco-time-master.csv")


def test_master_curve_shifts_and_laws_equal_the_cli():
    out = fitcli("fit", "--data", RAW, "--format", "pyvisco", "--master-curve", "--reference-c", 20,
                 "--model", "prony", "--terms", 4, "--shifts-out", work("shifts.csv"), "--out", work("mc.json"))
    raw = fitlib.read_table(RAW, format="pyvisco")
    curve = fitlib.build_master_curve(raw, fitlib.MasterCurveOptions(reference_C=20.0))
    assert curve.shift_table() in out, curve.shift_table()
    with open(work("shifts.csv")) as f:
        assert curve.shift_factors().to_csv() == f.read()
    assert len(curve.isotherms) == 21 and len(curve.master) == len(raw)
    # The card's WLF constants are the curve's, and the module's own WLF fit of its points.
    card = json.load(open(work("mc.json")))
    law = card["temperature"]
    assert (law["C1"], law["C2_K"]) == (curve.wlf["C1"], curve.wlf["C2_K"]), (law, curve.wlf)
    again = fitlib.fit_wlf(curve.temperature_C, curve.log10_aT, 20.0)
    assert again["C1"] == curve.wlf["C1"] and again["C2_K"] == curve.wlf["C2_K"]
    # A polynomial of degree 2 through exact quadratic shifts is found to round-off.
    T = np.array([-20.0, 0.0, 20.0, 40.0, 60.0])
    poly = fitlib.fit_polynomial_shift(T, -0.1 * (T - 20.0) + 1e-3 * (T - 20.0) ** 2, 20.0, 2)
    assert np.allclose(poly["coefficients"], [-0.1, 1e-3], rtol=1e-9), poly


def test_relaxation_master_curve_equals_the_cli():
    time_raw = source("datasets", "materials", "pyvisco-time-raw.csv")
    out = fitcli("fit", "--data", time_raw, "--format", "pyvisco", "--master-curve", "--reference-c", 20,
                 "--model", "prony", "--terms", 4, "--shifts-out", work("time-shifts.csv"), "--out", work("tm.json"))
    curve = fitlib.build_relaxation_master_curve(fitlib.read_relaxation_table(time_raw),
                                                 fitlib.MasterCurveOptions(reference_C=20.0))
    assert curve.shift_table() in out, curve.shift_table()
    with open(work("time-shifts.csv")) as f:
        assert curve.shift_factors().to_csv() == f.read()
    assert len(curve.isotherms) == 21 and len(curve.master) == 0


def test_shift_file_read_write_and_given_shifts_equal_the_cli():
    given = source("datasets", "materials", "pyvisco-freq-master-shift-factors.csv")
    shifts = fitlib.read_shift_factors(given)
    assert len(shifts) == len(shifts.temperature_C) > 2
    again = fitlib.parse_shift_factors(shifts.to_csv(), "again.csv")
    assert list(again.log10_aT) == list(shifts.log10_aT)  # exact round trip
    made = fitlib.ShiftFactorTable([0.0, 50.0], [2.0, -1.5])
    made.save(work("made.csv"))
    assert list(fitlib.read_shift_factors(work("made.csv")).log10_aT) == [2.0, -1.5]
    assert made.interpolate(25.0) == 0.25
    fitcli("fit", "--data", RAW, "--format", "pyvisco", "--shifts", given, "--reference-c", 20,
           "--model", "prony", "--terms", 4, "--shifts-out", work("given-out.csv"), "--out", work("given.json"))
    raw = fitlib.read_table(RAW, format="pyvisco")
    curve = fitlib.master_curve_from_shift_factors(raw, shifts, 20.0)
    with open(work("given-out.csv")) as f:
        assert curve.shift_factors().to_csv() == f.read()


def test_relaxation_fit_and_times_equal_the_cli():
    fitcli("fit", "--data", TIME_MASTER, "--format", "pyvisco", "--model", "prony", "--terms", 4,
           "--out", work("relax.json"))
    cli = fitlib.load_card(work("relax.json"))
    table = fitlib.read_relaxation_table(TIME_MASTER)
    assert len(table) == len(table.time_s) and set(table.mode) == {"uniaxial"}
    model = fitlib.make_model("prony", {"terms": 4, "mode": "uniaxial", "temperature_law": "none"})
    result = fitlib.fit_relaxation(model, table, fitlib.FitOptions())
    assert np.allclose(result.values, cli.values(), rtol=1e-9, atol=0), (result.values, cli.values())
    measures = fitlib.measure_relaxation(model, result.values, table)
    assert measures["rms_log10"] == result.metrics.rms_log10_storage
    # M(t) of the card at chosen times = fitcli eval --time-s.
    times = [1e-6, 1e-2, 1.0, 1e3]
    rows = json.loads(fitcli("eval", "--card", work("relax.json"), "--mode", "uniaxial", "--time-s", *times,
                             "--json"))["rows"]
    mine = cli.model().relaxation_modulus(cli.values(), times)
    assert [r["relaxation_modulus_MPa"] for r in rows] == list(mine)


# ---- segment and life (scene/segment_case.hpp, scene/planner.hpp) -------------------------------
def test_segment_case_stresses_equal_the_cli():
    path = source("datasets", "segment", "bend-40mm.toml")
    cli = json.loads(fitcli("segment", "--scene", path, "--json"))
    mine = fitlib.segment_case(fitlib.load_scene(path))
    assert mine["points"] == [p["name"] for p in cli["points"]]
    for key in ("sigma11_radial_MPa", "sigma22_longitudinal_MPa", "sigma12_MPa", "sigma33_MPa", "principal_max_MPa"):
        assert isinstance(mine[key], np.ndarray)
        assert list(mine[key]) == [p[key] for p in cli["points"]], key
    assert mine["summary"] == cli
    assert mine["c_N_per_mm"] == cli["stiffness"]["c_N_per_mm"]


def test_life_per_mode_and_governing_mode_equal_the_cli():
    path = source("datasets", "drives", "ref-0500-medium.toml")
    cli = json.loads(fitcli("life", "--scene", path, "--out-dir", work("life"), "--json"))
    scene = fitlib.load_scene(path)
    result = fitlib.run_life(scene)
    life = result.life
    assert life["governing"] == cli["governing_mode"] and life["fidelity"] == cli["fidelity"]
    assert life["life_cycles"] == cli["life_cycles"] and life["life_h"] == cli["life_h"]
    assert sorted(life["modes"]) == sorted(m["mode"] for m in cli["modes"])
    for m in cli["modes"]:
        mine = life["modes"][m["mode"]]
        assert mine["design_point"] == m["design_point"]["name"]
        assert (mine["x_mm"], mine["y_mm"]) == (m["design_point"]["x_mm"], m["design_point"]["y_mm"])
        assert mine["life_cycles"] == m["life_cycles"] and mine["sum_terms"] == m["sum_terms"]
        assert list(mine["peak_stress_MPa"]) == [p["effective_stress_MPa"] for p in m["peaks"]]
    assert fitlib.life_json(scene, result) == cli
    assert fitlib.life_json(scene, fitlib.run_life(path)) == cli  # the scene file's path does as well
    assert fitlib.load_scene(path).run().life is None  # not asked for: not computed


def test_fit_life_constants_equals_the_cli():
    path = source("datasets", "life-tests", "synthetic-beam.csv")
    cli = json.loads(fitcli("life-fit", "--observed", path, "--out", work("life-card.json"), "--json"))
    mine = fitlib.fit_life_constants(path)
    assert mine["card"]["modes"] == cli["modes"] and mine["warnings"] == cli["warnings"]
    assert mine["card"]["provenance"]["observed"] == cli["provenance"]["observed"]
    assert [f["mode"] for f in mine["fits"]] == ["radial_crack", "separation"]
    assert len(mine["cases"]) == 30 and isinstance(mine["predicted_cycles"], np.ndarray)
    assert mine["runout"] == [False] * 30 and all(f["runouts"] == 0 for f in mine["fits"])
    # the synthetic lives scatter by 10^(0.1 z) around the truth: the fit predicts them within a factor 3
    assert np.all(np.abs(np.log10(mine["predicted_cycles"] / mine["observed_cycles"])) < 0.5)
    e = expect(fitlib.InputError, lambda: fitlib.fit_life_constants(source("datasets", "drives", "ref-0500-medium.toml")))
    assert e.exit_code == 3



def test_scene_warnings_equal_the_cli():
    # At 110 degC the Fritzson stiffness laws are extrapolated: the same warnings in Python and life.json
    # (the built-in card's beam-level constants are calibrated, so no off-scale warning).
    text = open(source("datasets", "drives", "ref-0500-medium.toml")).read().replace("temperature_C = 80", "temperature_C = 110")
    path = work("hot.toml")
    with open(path, "w") as f:
        f.write(text)
    cli = json.loads(fitcli("life", "--scene", path, "--out-dir", work("hot-life"), "--json"))
    result = fitlib.run_life(fitlib.load_scene(path))
    assert result.warnings == cli["warnings"] and len(result.warnings) == 1
    assert "at 110 degC they are extrapolated" in result.warnings[0]
    assert fitlib.load_scene(source("datasets", "drives", "ref-0500-medium.toml")).run().warnings == []

def test_hyperelastic_fit_equals_the_cli():
    data = source("datasets", "materials", "treloar1944-czhao.csv")
    card, warnings = fitlib.fit_hyperelastic_card([data], "ogden", terms=3, name="ogden-fit")
    out = work("og3.json")
    fitcli("fit", "--data", data, "--model", "ogden", "--terms", "3", "--out", out)
    cli = fitlib.load_card(out)
    assert list(card.values()) == list(cli.values()) and warnings == []
    stretch = [1.1, 1.5, 2.0, 3.0]
    rows = list(csv.DictReader(io.StringIO(fitcli("eval", "--card", out, "--mode", "planar", "--stretch", "1.1,1.5,2,3"))))
    assert list(fitlib.nominal_stress(card, "planar", stretch)) == [float(r["nominal_stress_MPa"]) for r in rows]

def main():
    tests = [(name, f) for name, f in globals().items() if name.startswith("test_") and callable(f)]
    failed = 0
    for name, f in tests:
        try:
            f()
            print(f"ok   {name}")
        except Exception:  # noqa: BLE001 - report every failure and go on
            failed += 1
            print(f"FAIL {name}")
            traceback.print_exc()
    print(f"{len(tests) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
