#!/usr/bin/env python3
"""Writes the waveform fixtures of this folder from closed-form sinusoids (see README.md).

Run from this folder: python3 generate.py. Numbers are written with repr() (shortest text that
reads back to the same double), so the files reproduce the formulas to the last bit.
"""
import json
import math


def samples(f_Hz, n, periods):
    dt = periods / (f_Hz * n)
    return [i * dt for i in range(n)]


def write(name, header_lines, columns, rows):
    with open(name, "w", newline="\n") as out:
        for line in header_lines:
            out.write("# " + line + "\n")
        out.write(",".join(columns) + "\n")
        for row in rows:
            out.write(",".join(repr(v) for v in row) + "\n")


# 1. Double-sandwich shear (thesis blocks 50.8 x 12.7 x 12.7 mm, two specimens), 3 Hz,
#    1024 samples over 5 periods (thesis: about 5 periods in a 1024-element array).
#    gamma = 0.045 sin(theta), tau = 0.045 (4 sin(theta) + 0.8 cos(theta)) MPa, theta = 2 pi f t + 0.25
#    -> G' = 4 MPa, G'' = 0.8 MPa. F = n A tau, u = h gamma.
f, A, h, n = 3.0, 50.8 * 12.7, 12.7, 2
rows = []
for t in samples(f, 1024, 5):
    th = 2 * math.pi * f * t + 0.25
    gamma = 0.045 * math.sin(th)
    tau = 0.045 * (4.0 * math.sin(th) + 0.8 * math.cos(th))
    rows.append((t, n * A * tau, h * gamma))
write("shear_sandwich_3Hz.csv",
      ["double-sandwich shear, G' = 4 MPa, G'' = 0.8 MPa, gamma_a = 0.045 (generate.py)",
       "mode = shear", "area_mm2 = 645.16", "thickness_mm = 12.7", "n_specimens = 2",
       "temperature_C = 23", "material = material-1", "specimen = S1", "orientation = 12"],
      ["time_s", "force_N", "displacement_mm"], rows)

# 2. Bonded compression with a mean strain of one amplitude (cycle from 0 to -2 eps_a), 34 Hz,
#    512 samples over 5 periods. eps = -0.01 + 0.01 sin(theta), theta = 2 pi f t,
#    sigma = 10 * (-0.01) + 0.01 (12 sin(theta) + 2.4 cos(theta)) MPa
#    -> E' = 12, E'' = 2.4, E_m = 10 MPa. F = A sigma (A = 100 mm2), u = L eps (L = 10 mm).
#    Specimen metadata in the JSON sidecar compression_34Hz.json.
f, A, L = 34.0, 100.0, 10.0
rows = []
for t in samples(f, 512, 5):
    th = 2 * math.pi * f * t
    eps = -0.01 + 0.01 * math.sin(th)
    sigma = 10.0 * -0.01 + 0.01 * (12.0 * math.sin(th) + 2.4 * math.cos(th))
    rows.append((t, A * sigma, L * eps))
write("compression_34Hz.csv", ["bonded compression, E' = 12, E'' = 2.4, E_m = 10 MPa (generate.py)"],
      ["time_s", "force_N", "displacement_mm"], rows)
with open("compression_34Hz.json", "w") as out:
    json.dump({"mode": "compression", "area_mm2": 100, "length_mm": 10, "temperature_C": 80,
               "orientation": "22", "material": "material-1", "specimen": "C7"}, out, indent=2)
    out.write("\n")

# 3. Stress and strain directly, with a third harmonic in the stress (a nonlinear response),
#    60 Hz, 1024 samples over 5 periods. eps = 0.02 sin(theta),
#    sigma = 0.02 (5 sin(theta) + 1 cos(theta)) + 0.01 sin(3 theta + 0.7) MPa.
f = 60.0
rows = []
for t in samples(f, 1024, 5):
    th = 2 * math.pi * f * t
    rows.append((t, 0.02 * (5.0 * math.sin(th) + 1.0 * math.cos(th)) + 0.01 * math.sin(3 * th + 0.7),
                 0.02 * math.sin(th)))
write("stress_strain_harmonic_60Hz.csv",
      ["stress/strain input with a third harmonic in the stress (generate.py)", "mode = uniaxial"],
      ["time_s", "stress_MPa", "strain"], rows)
