#!/usr/bin/env python3
"""Plots measured storage and loss moduli and tan delta against a fitted card's curve.

usage: plot_fit.py DATA.csv FORMAT CURVE.csv OUT.png [TITLE]
  DATA.csv   the table that was fitted (FORMAT native or pyvisco)
  CURVE.csv  `fitcli eval` output for the card on a dense frequency grid
"""
import csv
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    with open(path, encoding="utf-8-sig") as f:
        lines = [l for l in f if l.strip() and not l.lstrip().startswith("#")]
    return list(csv.reader(lines, skipinitialspace=True))


def measured(path, fmt):
    rows = read_rows(path)
    head = [h.strip() for h in rows[0]]
    body = rows[2:] if fmt == "pyvisco" else rows[1:]
    if fmt == "pyvisco":
        f, s, l = head.index("f"), head.index("E_stor" if "E_stor" in head else "G_stor"), \
            head.index("E_loss" if "E_loss" in head else "G_loss")
    else:
        f, s, l = head.index("frequency_Hz"), head.index("storage_MPa"), head.index("loss_MPa")
    return ([float(r[f]) for r in body], [float(r[s]) for r in body], [float(r[l]) for r in body])


def main():
    if len(sys.argv) < 5:
        print(__doc__, file=sys.stderr)
        return 2
    data, fmt, curve, out = sys.argv[1:5]
    title = sys.argv[5] if len(sys.argv) > 5 else ""
    f, s, l = measured(data, fmt)
    rows = read_rows(curve)
    head = rows[0]
    cf = [float(r[head.index("frequency_Hz")]) for r in rows[1:]]
    cs = [float(r[head.index("storage_MPa")]) for r in rows[1:]]
    cl = [float(r[head.index("loss_MPa")]) for r in rows[1:]]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    ax[0].loglog(f, s, "o", ms=3, label="storage, measured")
    ax[0].loglog(f, l, "s", ms=3, label="loss, measured")
    ax[0].loglog(cf, cs, "-", label="storage, card")
    ax[0].loglog(cf, cl, "-", label="loss, card")
    ax[0].set_xlabel("frequency / Hz")
    ax[0].set_ylabel("modulus / MPa")
    ax[0].legend(fontsize=8)
    ax[1].loglog(f, [b / a for a, b in zip(s, l)], "o", ms=3, label="measured")
    ax[1].loglog(cf, [b / a for a, b in zip(cs, cl)], "-", label="card")
    ax[1].set_xlabel("frequency / Hz")
    ax[1].set_ylabel("tan delta")
    ax[1].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"plot written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
