#!/usr/bin/env python3
"""The Python module as safe as the CLI (issue 37; run by ctest as `python_checks`).

Each bad call that crashed, returned NaN, raised a raw C++ or SystemError, or ran unbounded must
raise fitlib's typed error (InputError, UsageError: exit codes 3 and 2 of the CLI) before any work;
every public name has a docstring; tables build from NumPy arrays with the reader's checks.
Environment: PYTHONPATH = <build>/python, FITLIB_ROOT = the source tree.
"""
import inspect
import math
import os
import re
import shutil
import sys
import tempfile
import time
import traceback
import warnings

import numpy as np

import fitlib

ROOT = os.environ["FITLIB_ROOT"]
CARD = os.path.join(ROOT, "tests", "data", "bad", "card", "ok.json")          # a Prony card
WINDOW_CARD = os.path.join(ROOT, "tests", "data", "bad", "card", "window_23_60.json")
FRITZSON = os.path.join(ROOT, "datasets", "cards", "material-2-true.json")
SWEEP = os.path.join(ROOT, "tests", "data", "sweep", "small.toml")
SEGMENT = os.path.join(ROOT, "datasets", "segment", "bend-40mm.toml")
MINIMAL_SCENE = os.path.join(ROOT, "tests", "data", "scenes", "minimal.toml")
WORK = os.path.join(tempfile.gettempdir(), f"fitlib-python-checks-{os.getpid()}")  # this process's own


def raises(error, call, *words):
    """call() raises `error` (not a subclass of something else) whose text holds every word, fast."""
    t0 = time.time()
    try:
        call()
    except error as e:
        for w in words:
            assert w in str(e), f"{w!r} not in {e}"
        assert time.time() - t0 < 5, "refused only after the work"
        return e
    except Exception as e:  # noqa: BLE001
        raise AssertionError(f"{type(e).__name__}: {e} instead of {error.__name__}") from e
    raise AssertionError(f"no {error.__name__}")


def test_empty_shift_table_is_an_error_not_a_segfault():
    raises(fitlib.InputError, lambda: fitlib.ShiftFactorTable([], []).interpolate(20.0), "no shift factors")
    raises(fitlib.UsageError, lambda: fitlib.ShiftFactorTable([20, 30], [0, -1]).interpolate(float("nan")))
    raises(fitlib.UsageError, lambda: fitlib.ShiftFactorTable([20], [0, 1]), "differ in length")
    raises(fitlib.UsageError, lambda: fitlib.ShiftFactorTable([float("nan")], [0]), "temperature_C")


def test_shift_laws_refuse_too_few_or_mismatched_shifts():
    for call in (lambda: fitlib.fit_wlf([], [], 20.0), lambda: fitlib.fit_wlf([10, 20], [1, 0], 20.0),
                 lambda: fitlib.fit_arrhenius([20], [0], 20.0),
                 lambda: fitlib.fit_polynomial_shift([10, 20], [1, 0], 20.0, degree=3)):
        raises(fitlib.UsageError, call, "shift")
    raises(fitlib.UsageError, lambda: fitlib.fit_wlf([10, 20, 30], [1, 0], 20.0), "differ in length")
    raises(fitlib.UsageError, lambda: fitlib.fit_wlf([10, 20, 30], [1, float("inf"), -1], 20.0), "log10_aT")
    wlf = fitlib.fit_wlf([0, 20, 40, 60], [2.0, 0.0, -1.5, -2.6], 20.0)  # a real fit stays finite
    assert all(math.isfinite(v) for v in wlf.values()), wlf


def test_material_point_arguments_have_the_cli_ranges_and_work_cap():
    card = fitlib.load_card(CARD)
    point = fitlib.make_material_point(card.model(), card.values(), bulk_modulus_MPa=2000.0)
    raises(fitlib.UsageError, lambda: fitlib.drive_test(point, steps_per_cycle=-5), "steps_per_cycle")
    raises(fitlib.UsageError, lambda: fitlib.drive_test(point, cycles=0), "cycles")
    raises(fitlib.InputError, lambda: fitlib.drive_test(point, cycles=100000, steps_per_cycle=100), "work cap",
           "cycles x steps_per_cycle", "s estimated")
    raises(fitlib.InputError, lambda: fitlib.drive(point, np.arange(2e6), [("strain", np.zeros(2000000))] + [None] * 5),
           "work cap", "len(time_s)")
    # By cost, not steps: 5e5 steps of a uniaxial test are within the cap for the Prony card's point
    # (it runs) and above it for a fractional Zener point (1548 state values, about 10 s estimated).
    long = fitlib.drive_test(point, mode="uniaxial", cycles=500, steps_per_cycle=1000)
    assert len(long["time_s"]) == 500 * 1000 + 1 and np.all(np.isfinite(long["stress_MPa"]))
    zener = fitlib.make_material_point(fitlib.make_model("fractional-zener"),
                                       fitlib.make_model("fractional-zener").default_parameters(),
                                       bulk_modulus_MPa=2000.0)
    raises(fitlib.InputError, lambda: fitlib.drive_test(zener, mode="uniaxial", cycles=500, steps_per_cycle=1000),
           "work cap", "1548 state values")
    raises(fitlib.UsageError, lambda: fitlib.drive_test(point, amplitude=1e9), "amplitude")
    raises(fitlib.UsageError, lambda: fitlib.drive_test(point, frequency_Hz=0.0), "frequency_Hz")
    raises(fitlib.UsageError, lambda: fitlib.drive_test(point, temperature_C=-300.0), "temperature_C")
    out = fitlib.drive_test(point, cycles=1, steps_per_cycle=20)
    assert np.all(np.isfinite(out["stress_MPa"]))
    fritzson = fitlib.load_card(FRITZSON)
    raises(fitlib.UsageError, lambda: fitlib.fritzson_thesis_case(fritzson, "7.1", steps_per_cycle=10**9),
           "steps_per_cycle")
    raises(fitlib.InputError, lambda: fitlib.fritzson_thesis_case(fritzson, "7.1", steps_per_cycle=200000),
           "work cap", "steps_per_cycle")


def test_grid_and_sweep_are_capped_before_work():
    card = fitlib.load_card(CARD)
    f = np.logspace(-1, 2, 10000)
    raises(fitlib.InputError, lambda: fitlib.card_grid(card, f, np.linspace(20, 30, 1000)), "work cap", "points")
    # Card.eval broadcasts its arguments: two arrays of 10^4 values are 10^8 points (ran on, 20 s per
    # 10^8 before the cap); the cap of card_grid, before any point. 10^6 points still run.
    raises(fitlib.InputError, lambda: card.eval(f[:, None], np.linspace(20, 30, 10000)[None, :]), "work cap", "points")
    model = card.model()
    raises(fitlib.InputError, lambda: model.moduli(card.values(), f[:, None], np.ones(1000)[None, :]), "work cap")
    raises(fitlib.InputError, lambda: model.relaxation_modulus(card.values(), f[:, None], np.ones(1000)[None, :]),
           "work cap")
    assert card.eval(np.full(10**6, 1.0))["storage_MPa"].shape == (10**6,)
    raises(fitlib.UsageError, lambda: fitlib.sweep(SWEEP, threads=0), "threads")
    raises(fitlib.UsageError, lambda: fitlib.sweep(SWEEP, threads=-3), "threads")
    raises(fitlib.UsageError, lambda: fitlib.accumulation_map("box", cycle_points=100000, omega_points=100000),
           "work cap")
    raises(fitlib.UsageError, lambda: fitlib.accumulation_map("box", cycle_points=0), "cycle_points")


def test_card_eval_and_export_refuse_beyond_the_window_as_the_cli():
    card = fitlib.load_card(WINDOW_CARD)
    window = card.fit["data_window"]
    inside = window["frequency_Hz"][0]
    raises(fitlib.InputError, lambda: card.eval(1e6), "fit.data_window", "allow_extrapolation")
    e = raises(fitlib.InputError, lambda: card.eval(inside, temperature_C=200.0), "allow_extrapolation")
    assert e.key.startswith("fit.data_window."), e.key
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        out = card.eval(1e6, allow_extrapolation=True)
    assert np.all(np.isfinite(out["storage_MPa"])) and any("extrapolating" in str(w.message) for w in seen)
    raises(fitlib.InputError, lambda: card.export("abaqus", temperature_C=200.0), "allow_extrapolation")
    raises(fitlib.UsageError, lambda: card.export("abaqus", poisson_ratio=0.7), "poisson_ratio")
    raises(fitlib.UsageError, lambda: card.export("ansys", material_id=0), "material_id")


def test_card_eval_converts_modes_as_the_cli():
    card = fitlib.load_card(CARD)  # a shear card without K: E* from G* at nu = 0.4995
    g = card.eval(1.0)["storage_MPa"]
    e = card.eval(1.0, mode="uniaxial")["storage_MPa"]
    assert 2.9 < float(e / g) < 3.01, (g, e)


def test_text_for_a_number_is_a_type_error_not_a_system_error():
    card = fitlib.load_card(CARD)
    raises(TypeError, lambda: card.eval("abc"), "abc")
    raises(TypeError, lambda: card.eval(1.0, temperature_C="warm"), "warm")
    raises(TypeError, lambda: card.model().moduli(card.values(), "abc"), "abc")


def test_none_or_text_for_a_frequency_time_or_temperature_is_a_type_error_naming_it():
    """card.eval(None) answered "nan Hz" (NumPy made None a NaN); every entry point that takes a
    frequency, time or temperature raises TypeError naming the argument for None, text, a bool or a
    list holding None. A temperature left out (None, the default) stays the reference."""
    card = fitlib.load_card(CARD)
    model, p = card.model(), card.values()
    point = fitlib.make_material_point(model, p, bulk_modulus_MPa=2000.0)
    shifts = fitlib.ShiftFactorTable([10, 20, 30], [1.0, 0.0, -1.0])
    calls = {
        "frequency_Hz": [lambda v: card.eval(v), lambda v: model.moduli(p, v), lambda v: fitlib.card_grid(card, v),
                         lambda v: fitlib.Table(v, [1.0], [0.1]), lambda v: point.complex_stiffness(v),
                         lambda v: fitlib.make_material_point(model, p, frequency_Hz=v, bulk_modulus_MPa=2000.0),
                         lambda v: fitlib.drive_test(point, frequency_Hz=v, cycles=1, steps_per_cycle=20),
                         lambda v: model.damage_drivers(p, frequency_Hz=v)],
        "omega_min": [lambda v: fitlib.accumulation_map("box", omega_min=v, omega_points=3, cycle_points=3)],
        "omega_max": [lambda v: fitlib.accumulation_map("box", omega_max=v, omega_points=3, cycle_points=3)],
        "time_s": [lambda v: model.relaxation_modulus(p, v), lambda v: model.creep_compliance(p, v),
                   lambda v: fitlib.drive(point, v, [("strain", [0.0])] + [None] * 5)],
        "dt_s": [lambda v: point.update(point.initial_state(), np.zeros(6), v)],
        "temperature_C": [lambda v: shifts.interpolate(v), lambda v: fitlib.ShiftFactorTable(v, [1.0, 0.0]),
                          lambda v: fitlib.given_log10_aT(shifts, v, 20.0),
                          lambda v: fitlib.fit_wlf(v, [2.0, 0.0, -1.5], 20.0)],
        "reference_C": [lambda v: fitlib.fit_wlf([0, 20, 40], [2.0, 0.0, -1.5], v),
                        lambda v: fitlib.fit_arrhenius([0, 20], [2.0, 0.0], v),
                        lambda v: fitlib.given_log10_aT(shifts, 20.0, v)],
    }
    # Where a temperature may be left out, None is the reference; text, a bool, None in a list are not.
    optional = [lambda v: card.eval(1.0, temperature_C=v), lambda v: model.moduli(p, 1.0, temperature_C=v),
                lambda v: model.relaxation_modulus(p, 1.0, temperature_C=v), lambda v: fitlib.card_grid(card, 1.0, v),
                lambda v: point.complex_stiffness(1.0, temperature_C=v), lambda v: card.export("abaqus", temperature_C=v),
                lambda v: fitlib.drive_test(point, temperature_C=v, cycles=1, steps_per_cycle=20),
                lambda v: fitlib.make_material_point(model, p, temperature_C=v, bulk_modulus_MPa=2000.0),
                lambda v: fitlib.ShiftFactorTable([10, 20], [1.0, 0.0], reference_C=v)]
    for argument, entries, bad_values in [(a, e, (None, "abc", True, [1.0, None])) for a, e in calls.items()] + [
            ("temperature_C", optional[:-1], ("abc", True, [1.0, None])), ("reference_C", optional[-1:], ("abc", True))]:
        for call in entries:
            for bad in bad_values:
                e = raises(TypeError, lambda: call(bad), argument + " must be")
                assert "nan" not in str(e), e
    # Left out, a temperature is the reference: None as before, the same numbers as no argument.
    assert np.array_equal(card.eval(1.0, temperature_C=None)["storage_MPa"], card.eval(1.0)["storage_MPa"])
    assert np.array_equal(point.complex_stiffness(1.0, temperature_C=None), point.complex_stiffness(1.0))
    out = fitlib.drive_test(point, cycles=1, steps_per_cycle=20, temperature_C=None, frequency_Hz=np.float32(2))
    assert np.all(np.isfinite(out["stress_MPa"]))
    assert card.eval(np.int64(1))["storage_MPa"] == card.eval(1.0)["storage_MPa"]


def test_a_wrong_type_for_an_options_field_is_a_type_error_naming_it():
    """FitOptions(tolerance=None) raised pybind11's "(): incompatible function arguments" that named
    no field, and polish=None or tolerance=True were taken as False and 1.0: every field of every
    options class, set as a keyword or an attribute, raises TypeError naming it for a wrong type (a
    bool field in the words of a bool argument: "must be a bool (True or False), got None")."""
    bad_values = {float: (None, "abc", True, [1.0, None]), int: (None, "abc", True, 2.5),
                  bool: (None, "abc", 1), str: (None, 1, True), list: (None, "abc", [1])}
    for options in (fitlib.FitOptions, fitlib.TermOptions, fitlib.MasterCurveOptions):
        fields = [n for n in dir(options()) if not n.startswith("_")]
        assert len(fields) >= 8, fields
        for field in fields:
            kind = type(getattr(options(), field))
            words = field + (" must be a bool (True or False), got " if kind is bool else " must be")
            for bad in bad_values[kind]:
                raises(TypeError, lambda: options(**{field: bad}), words)
                raises(TypeError, lambda: setattr(options(), field, bad), words)
    # NumPy scalars are numbers, integers and bools as before; the value is the one given.
    o = fitlib.FitOptions(seed=np.uint64(7), multistart=np.int32(3), tolerance=np.float32(0.5),
                          polish=np.bool_(False), fixed=["tau_1"], backend="ceres")
    assert (o.seed, o.multistart, o.tolerance, o.polish, o.fixed, o.backend) == (7, 3, 0.5, False, ["tau_1"], "ceres")
    assert fitlib.TermOptions(smoothness=2).smoothness == 2.0
    assert math.isnan(fitlib.MasterCurveOptions(reference_C=float("nan")).reference_C)


def test_a_wrong_type_for_a_number_or_an_integer_argument_is_a_type_error_naming_it():
    """accumulation_map(kappa=None), drive_test(cycles=2.5), card.export(poisson_ratio="a") raised
    pybind11's "incompatible function arguments" that named no argument, and a bool was taken as 1:
    every plain number or integer argument raises TypeError naming it (an integer: not a float, not a bool).
    segment_case's loads, which may be left out, raised a RuntimeError ("Unable to cast") for text."""
    card = fitlib.load_card(CARD)
    model, p = card.model(), card.values()
    point = fitlib.make_material_point(model, p, bulk_modulus_MPa=2000.0)
    shifts = fitlib.ShiftFactorTable([10, 20, 30], [1.0, 0.0, -1.0])
    relaxation = fitlib.read_relaxation_table(os.path.join(ROOT, "datasets", "materials", "pyvisco-time-raw.csv"))
    result = fitlib.fit(model, fitlib.Table([0.1, 1.0, 10.0], [2.0, 2.5, 3.0], [0.2, 0.3, 0.4]))
    accumulate = lambda **kw: fitlib.accumulation_map("box", **{"omega_points": 3, "cycle_points": 3, **kw})  # noqa: E731
    drive = lambda **kw: fitlib.drive_test(point, **{"cycles": 1, "steps_per_cycle": 20, **kw})  # noqa: E731
    numbers = {
        "shear_stress_MPa": [lambda v: accumulate(shear_stress_MPa=v)], "kappa": [lambda v: accumulate(kappa=v)],
        "strain_limit": [lambda v: accumulate(strain_limit=v)],
        "amplitude": [lambda v: drive(amplitude=v)], "mean_strain": [lambda v: drive(mean_strain=v)],
        "bulk_modulus_MPa": [lambda v: fitlib.make_material_point(model, p, bulk_modulus_MPa=v)],
        "poisson_ratio": [lambda v: card.eval(1.0, poisson_ratio=v), lambda v: card.export("abaqus", poisson_ratio=v)],
        "density_t_per_mm3": [lambda v: card.export("abaqus", density_t_per_mm3=v)],
        "strain_amplitude": [lambda v: model.damage_drivers(p, strain_amplitude=v)],
        "level_tolerance": [lambda v: fitlib.fit_surface(np.zeros((4, 2)), np.zeros(4), ["a", "b"], level_tolerance=v)],
        "reference_C": [lambda v: fitlib.master_curve_from_shift_factors(fitlib.Table([1.0], [1.0], [0.1]), shifts, v),
                        lambda v: fitlib.shift_relaxation_table(relaxation, shifts, v)],
    }
    integers = {
        "cycles": [lambda v: accumulate(cycles=v), lambda v: drive(cycles=v)],
        "cycle_points": [lambda v: accumulate(cycle_points=v)], "omega_points": [lambda v: accumulate(omega_points=v)],
        "steps_per_cycle": [lambda v: drive(steps_per_cycle=v),
                            lambda v: fitlib.fritzson_thesis_case(fitlib.load_card(FRITZSON), "7.1", steps_per_cycle=v)],
        "material_id": [lambda v: card.export("ansys", material_id=v)],
        "degree": [lambda v: fitlib.fit_polynomial_shift([0, 20, 40, 60], [2.0, 0.0, -1.5, -2.6], 20.0, degree=v)],
        "polynomial_degree": [lambda v: fitlib.with_law_from_shifts(result, [0, 20, 40, 60], [2.0, 0.0, -1.5, -2.6],
                                                                    20.0, law="polynomial", polynomial_degree=v)],
        "terms": [lambda v: fitlib.fit_hyperelastic_card([], "ogden", terms=v)],
        "multistart": [lambda v: fitlib.fit_hyperelastic_card([], "ogden", multistart=v)],
        "seed": [lambda v: fitlib.fit_hyperelastic_card([], "ogden", seed=v)],
        "threads": [lambda v: fitlib.sweep(SWEEP, threads=v)],
    }
    segment = fitlib.load_scene(SEGMENT)  # a load left out (None) is the scene's: checked before the FE
    optional_numbers = {name: [lambda v, name=name: fitlib.segment_case(segment, **{name: v})]
                        for name in ("strain", "curvature_1_mm", "pressure_MPa")}
    for arguments, bad_values in ((numbers, (None, "abc", True, [1.0, None])), (integers, (None, "abc", True, 2.5)),
                                  (optional_numbers, ("abc", True, [1.0, None]))):
        for argument, entries in arguments.items():
            for call in entries:
                for bad in bad_values:
                    raises(TypeError, lambda: call(bad), argument + " must be")
    # NumPy scalars are numbers and integers as before.
    out = drive(amplitude=np.float32(0.02), mean_strain=np.int64(0), cycles=np.int32(1), steps_per_cycle=np.uint16(20))
    assert len(out["time_s"]) == 21 and np.all(np.isfinite(out["stress_MPa"]))
    assert accumulate(cycles=np.int64(100), kappa=3)["cycles"] is not None


def arguments(text):
    """[(name, type)] of a pybind11 signature's argument list "a: float = 1.0, b: List[str]": split at
    the commas outside brackets and quotes (defaults are reprs: "<fitlib.FitOptions object at ...>")."""
    parts, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(text):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "[(<{":
            depth += 1
        elif c in "])>}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    out = []
    for part in (p.strip() for p in parts):
        if ":" in part and not part.startswith("*"):
            name, rest = part.split(":", 1)
            out.append((name.strip(), rest.split(" = ")[0].strip()))
    return [(name, kind) for name, kind in out if name != "self"]


def signatures():
    """(function, [(argument, type)]) of every signature pybind11 wrote into a public function's or
    method's __doc__ (an overloaded function: one per overload); a method is named Class.method."""
    out = []

    def add(function, obj, short):
        for line in (getattr(obj, "__doc__", None) or "").splitlines():
            m = re.match(r"^\s*(?:\d+\. )?" + re.escape(short) + r"\((.*)\) -> ", line)
            if m:
                out.append((function, arguments(m.group(1))))

    for name in sorted(n for n in dir(fitlib) if not n.startswith("_")):
        obj = getattr(fitlib, name)
        if isinstance(obj, type):
            for attr, member in vars(obj).items():
                if callable(member) and (not attr.startswith("_") or attr in ("__init__", "__call__")):
                    add(f"{name}.{attr}", member, attr)
        elif type(obj).__name__ == "builtin_function_or_method":
            add(name, obj, name)
    assert len(out) > 50, len(out)  # 98 in December 2026
    return out


def python_bool_arguments():
    """(function, argument) of the package's own Python functions (fit_card) with a bool default."""
    return {(name, p.name) for name, f in vars(fitlib).items() if inspect.isfunction(f) and not name.startswith("_")
            for p in inspect.signature(f).parameters.values() if isinstance(p.default, bool)}


def test_a_wrong_type_for_a_bool_argument_is_a_type_error_naming_it():
    """card.eval(1e6, allow_extrapolation=None) was pybind11's False, read_table(..., skip_bad_rows=1)
    its True: every bool argument of every public function (found from the signatures, so that a new
    one must be listed here) raises TypeError naming it for None, 0, 1, text or a list; NumPy bools
    are bools."""
    card = fitlib.load_card(CARD)
    model = card.model()
    table = fitlib.Table([0.1, 1.0, 10.0], [2.0, 2.5, 3.0], [0.2, 0.3, 0.4])
    result = fitlib.fit(model, table)
    x = np.array([[a, b] for a in (0.0, 0.5, 1.0) for b in (1.0, 2.0, 3.0)])
    surface = fitlib.fit_surface(x, x[:, 0] + x[:, 1], ["a", "b"])
    scene = fitlib.load_scene(MINIMAL_SCENE)
    run = scene.run()
    missing = os.path.join(WORK, "no-such-file.csv")  # a check before the file is read
    calls = {
        ("Card.eval", "allow_extrapolation"): lambda v: card.eval(1.0, allow_extrapolation=v),
        ("Card.export", "allow_inadmissible"): lambda v: card.export("abaqus", allow_inadmissible=v),
        ("Card.export", "allow_extrapolation"): lambda v: card.export("abaqus", allow_extrapolation=v),
        ("Surface.__call__", "allow_extrapolation"): lambda v: surface([0.5, 2.0], allow_extrapolation=v),
        ("Surface.evaluate", "allow_extrapolation"): lambda v: surface.evaluate([0.5, 2.0], allow_extrapolation=v),
        ("card_from_fit", "record_timing"): lambda v: fitlib.card_from_fit(result, fitlib.FitOptions(), table, "c",
                                                                          record_timing=v),
        ("fit_table_card", "record_timing"): lambda v: fitlib.fit_table_card(
            table, "prony", "2", {}, fitlib.FitOptions(), fitlib.TermOptions(), "c", record_timing=v),
        ("fit_card", "record_timing"): lambda v: fitlib.fit_card(table, "prony", 2, record_timing=v),
        ("fit_card", "bulk_modulus"): lambda v: fitlib.fit_card(table, "prony", 2, bulk_modulus=v),
        ("fit_hyperelastic_card", "compressible"): lambda v: fitlib.fit_hyperelastic_card([], "ogden", compressible=v),
        ("fit_master_curve", "refine_shifts"): lambda v: fitlib.fit_master_curve(model, table, refine_shifts=v),
        ("read_table", "skip_bad_rows"): lambda v: fitlib.read_table(missing, skip_bad_rows=v),
        ("read_table", "allow_unknown_columns"): lambda v: fitlib.read_table(missing, allow_unknown_columns=v),
        ("fit_life_constants", "fix_n"): lambda v: fitlib.fit_life_constants(missing, fix_n=v),
        ("fit_life_constants", "fix_b"): lambda v: fitlib.fit_life_constants(missing, fix_b=v),
        ("life_json", "record_timing"): lambda v: fitlib.life_json(scene, run, record_timing=v),
        ("write_scene_outputs", "record_timing"): lambda v: fitlib.write_scene_outputs(
            scene, run, os.path.join(WORK, "no-such-folder"), record_timing=v),
        ("sweep", "csv"): lambda v: fitlib.sweep(os.path.join(WORK, "no-such-sweep.toml"), csv=v),
    }
    found = {(f, a) for f, args in signatures() for a, kind in args if "bool" in kind} | python_bool_arguments()
    assert found == set(calls), f"not tested: {sorted(found - set(calls))}, not bool: {sorted(set(calls) - found)}"
    for (function, argument), call in sorted(calls.items()):
        for bad in (None, 0, 1, "yes", [True]):
            raises(TypeError, lambda: call(bad), argument + " must be a bool (True or False), got " + repr(bad))
    # NumPy bools are bools: the value is the one given
    window = fitlib.load_card(WINDOW_CARD)
    raises(fitlib.InputError, lambda: window.eval(1e6, allow_extrapolation=np.bool_(False)), "allow_extrapolation")
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        assert np.all(np.isfinite(window.eval(1e6, allow_extrapolation=np.bool_(True))["storage_MPa"]))
    raises(fitlib.InputError, lambda: fitlib.read_table(missing, skip_bad_rows=np.bool_(False)), "no-such-file")


def test_the_life_of_a_result_without_one_is_a_usage_error():
    # life_json and life_text of scene.run() (no [outputs] life) raised a raw "bad optional access"
    scene = fitlib.load_scene(MINIMAL_SCENE)
    run = scene.run()
    assert run.life is None
    raises(fitlib.UsageError, lambda: fitlib.life_json(scene, run), "no life was computed")
    raises(fitlib.UsageError, lambda: fitlib.life_text(scene, run), "no life was computed")


def test_checked_arguments_show_their_python_type_in_the_signature():
    """Since the checks took py::object, help(fitlib.drive_test) showed `amplitude: object`: a number, an
    integer, a bool or an array of numbers shows float, int, bool, numpy.typing.ArrayLike (Optional[...]
    where None is allowed); `object` stays only where the argument takes objects of several kinds,
    listed here."""
    any_object = {
        # JSON documents (dicts; None for no options), passed through Python's json module
        ("card_from_json", "document"), ("surface_from_json", "document"), ("make_model", "options"),
        ("select_terms", "model_options"), ("select_relaxation_terms", "model_options"),
        ("fit_table_card", "model_options"), ("fit_surface", "constraints"),
        # a path or a list of paths; arrays, or a CSV path and its column's name
        ("read_table", "paths"), ("fit_surface", "x"), ("fit_surface", "y"),
    }
    found = {(f, a) for f, args in signatures() for a, kind in args if kind == "object"}
    assert found == any_object, f"object, not listed: {sorted(found - any_object)}; listed: {sorted(any_object - found)}"
    # The types of a few, as help() shows them.
    doc = fitlib.drive_test.__doc__
    for text in ("amplitude: float = 0.01", "cycles: int = 5", "steps_per_cycle: int = 200",
                 "temperature_C: Optional[float] = None", "frequency_Hz: float = 1.0"):
        assert text in doc, (text, doc)
    assert "allow_extrapolation: bool = False" in fitlib.Card.eval.__doc__
    assert "frequency_Hz: numpy.typing.ArrayLike, temperature_C: Optional[numpy.typing.ArrayLike] = None" \
        in fitlib.Card.eval.__doc__, fitlib.Card.eval.__doc__
    assert "threads: int = 1" in fitlib.sweep.__doc__ and "csv: bool = False" in fitlib.sweep.__doc__
    assert "reference_C: Optional[float] = None" in fitlib.ShiftFactorTable.__init__.__doc__

def test_tables_build_from_numpy_arrays_with_the_readers_checks():
    f = np.array([0.1, 1.0, 10.0])
    t = fitlib.Table(f, np.array([2.0, 2.5, 3.0]), np.array([0.2, 0.3, 0.4]), temperature_C=23.0)
    assert len(t) == 3 and list(t.mode) == ["shear"] * 3 and np.allclose(t.temperature_C, 23.0)
    assert np.array_equal(t.frequency_Hz, f)
    raises(fitlib.InputError, lambda: fitlib.Table(f, [2.0, float("nan"), 3.0], [0.2, 0.3, 0.4]), "arrays:3")
    raises(fitlib.InputError, lambda: fitlib.Table([-1.0], [2.0], [0.2]), "arrays:2")
    raises(ValueError, lambda: fitlib.Table(f, [2.0, 3.0], [0.2, 0.3, 0.4]))  # shapes that do not broadcast


def test_one_temperature_twice_and_one_file_twice_are_refused_as_by_the_cli():
    # the shift file's reader refuses a temperature listed twice; the arrays did not, and a law
    # "fitted" to shifts at one temperature came back as numbers (fit_wlf C1 0, C2 0.01 K)
    raises(fitlib.UsageError, lambda: fitlib.ShiftFactorTable([20, 20], [0, 1]), "20 is listed twice")
    raises(fitlib.UsageError, lambda: fitlib.fit_wlf([20, 20, 20], [0, 1, 2], 20.0), "listed twice")
    raises(fitlib.UsageError, lambda: fitlib.fit_arrhenius([30, 30], [0, 1], 20.0), "listed twice")
    # fitcli --data d.csv --data ./d.csv is exit 2: its rows would count twice
    table = os.path.join(ROOT, "datasets", "materials", "material-1.csv")
    dotted = os.path.join(ROOT, "datasets", ".", "materials", "material-1.csv")
    raises(fitlib.UsageError, lambda: fitlib.read_table([table, dotted]), "given twice")
    assert len(fitlib.read_table([table])) > 0


def test_segment_vtk_path_is_checked_as_fitcli_segment_vtk():
    # segment_case(vtk_path=...) wrote over whatever it was given, after the FE: the scene file, a
    # card the scene names, stdout's "-"; a missing folder failed only after the run
    work = os.path.join(WORK, "segment")
    os.makedirs(work)
    card = os.path.join(work, "card.json")
    shutil.copy(FRITZSON, card)
    scene_path = os.path.join(work, "bend.toml")
    with open(SEGMENT) as f:
        text = f.read()
    own_bottom = "bottom = {E_MPa = 20, nu = 0.4995}\n"
    assert own_bottom in text
    with open(scene_path, "w") as f:  # the bottom from a card, the cushion from [segment.materials]
        f.write(text.replace(own_bottom, "").replace("[segment]\n", '[belt.materials]\nbottom = "card.json"\n[segment]\n', 1))
    scene = fitlib.load_scene(scene_path)
    before = {p: open(p, "rb").read() for p in (card, scene_path)}
    os.link(card, os.path.join(work, "card-hard.json"))
    os.symlink(scene_path, os.path.join(work, "scene-link.toml"))
    raises(fitlib.UsageError, lambda: fitlib.segment_case(scene, vtk_path="-"), "vtk_path", "stdout")
    for path in (card, os.path.join(work, ".", "card.json"), os.path.join(work, "card-hard.json")):
        raises(fitlib.UsageError, lambda: fitlib.segment_case(scene, vtk_path=path), "vtk_path",
               "belt.materials.bottom", "its own input")
    for path in (scene_path, os.path.join(work, "scene-link.toml")):
        raises(fitlib.UsageError, lambda: fitlib.segment_case(scene, vtk_path=path), "scene file", "its own input")
    e = raises(fitlib.InputError, lambda: fitlib.segment_case(scene, vtk_path=os.path.join(work, "no-dir", "s.vtk")),
               "output folder does not exist")
    assert e.file.endswith(os.path.join("no-dir", "s.vtk")), e.file
    raises(fitlib.InputError, lambda: fitlib.segment_case(scene, vtk_path=work), "is a folder")
    assert {p: open(p, "rb").read() for p in (card, scene_path)} == before
    # a good path: an old file there is replaced whole, through a temporary that does not stay
    out = os.path.join(work, "s.vtk")
    with open(out, "w") as f:
        f.write("old\n" * 100000)
    plain = fitlib.segment_case(fitlib.load_scene(SEGMENT), vtk_path=out)
    with open(out) as f:
        vtk = f.read()
    assert vtk.startswith("# vtk DataFile") and "old" not in vtk, vtk[:80]
    assert f"CELLS {plain['elements']} " in vtk
    assert sorted(os.listdir(work)) == ["bend.toml", "card-hard.json", "card.json", "s.vtk", "scene-link.toml"]


def test_every_public_name_has_a_docstring():
    missing = []
    for name in sorted(n for n in dir(fitlib) if not n.startswith("_")):
        obj = getattr(fitlib, name)
        if isinstance(obj, (int, float, str)) or type(obj).__name__ == "module":
            continue
        # pybind11 writes the signature ("name(args) -> type") into every function's __doc__: a
        # docstring is text beyond it
        lines = (getattr(obj, "__doc__", None) or "").splitlines()
        text = [l for l in lines if l.strip() and not re.match(r"^\s*(\d+\. )?" + name + r"\(", l)
                and l.strip() != "Overloaded function."]
        if not text:
            missing.append(name)
    assert not missing, f"{len(missing)} public names without a docstring: {missing}"


def main():
    tests = [(n, f) for n, f in sorted(globals().items()) if n.startswith("test_")]
    failed = 0
    os.makedirs(WORK)
    for name, test in tests:
        try:
            test()
            print(f"ok   {name}")
        except Exception:  # noqa: BLE001
            failed += 1
            print(f"FAIL {name}\n{traceback.format_exc()}")
    shutil.rmtree(WORK, ignore_errors=True)
    print(f"{len(tests) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
