#!/usr/bin/env python3
"""Writes datasets/life-tests/synthetic-beam.csv: synthetic life tests of the medium reference
drive (pulley diameter, temperature, torque varied through scene-key columns), each "observed"
life the beam level's life under datasets/life-tests/fatigue-truth.json in its governing mode,
times 10^(0.1 z), z ~ N(0, 1) from random.Random(7). Not measured data (datasets/README.md).
Usage: scripts/make-life-tests.py [path/to/fitcli]"""
import json
import os
import random
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FITCLI = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "fitcli")
OUT = os.path.join(ROOT, "datasets", "life-tests", "synthetic-beam.csv")
BASE = open(os.path.join(ROOT, "datasets", "drives", "ref-0500-medium.toml")).read()
TRUTH = os.path.join(ROOT, "datasets", "life-tests", "fatigue-truth.json")

rng = random.Random(7)
rows = []
with tempfile.TemporaryDirectory() as tmp:
    for d in (80, 100, 125):
        for t in (60, 100):
            for m in (2.5, 5, 10, 20, 30):
                scene = (BASE.replace("temperature_C = 80", f"temperature_C = {t}")
                         .replace("torque_Nm = 15", f"torque_Nm = {m}")
                         .replace("pitch_diameter_mm = 100", f"pitch_diameter_mm = {d}"))
                path = os.path.join(tmp, "s.toml")
                with open(path, "w") as f:
                    f.write(scene + f'\n[life]\ncard = "{TRUTH}"\n')
                out = subprocess.run([FITCLI, "life", "--scene", path, "--json", "--out-dir", os.path.join(tmp, "o")],
                                     check=True, capture_output=True, text=True).stdout
                life = json.loads(out)
                mode = life["governing_mode"]
                hours = next(x["life_h"] for x in life["modes"] if x["mode"] == mode)
                observed = hours * 10 ** (0.1 * rng.gauss(0.0, 1.0))
                rows.append(f"D{d}-T{t}-M{m},../drives/ref-0500-medium.toml,{mode},{observed:.4g},{d},{d},{t},{m}")
with open(OUT, "w") as f:
    f.write("# Synthetic life tests (not measured): scripts/make-life-tests.py, truth fatigue-truth.json\n")
    f.write("case,scene,failure_mode,observed_h,drive.pulleys[0].pitch_diameter_mm,"
            "drive.pulleys[1].pitch_diameter_mm,conditions.temperature_C,drive.torque_Nm\n")
    f.write("\n".join(rows) + "\n")
print("wrote", OUT, len(rows), "tests")
