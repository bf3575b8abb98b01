#!/usr/bin/env python3
"""Runs a notebook headless (nbclient) in a work folder; fails if any cell raises or if the
executed notebook shows no figure inline (no image/png output: a notebook must show its plots).

usage: run_notebook.py NOTEBOOK.ipynb WORK_DIR
The executed copy is written to WORK_DIR/<name>.executed.ipynb for inspection; figures the
notebook saves land in WORK_DIR.
"""
import os
import sys

import nbformat
from nbclient import NotebookClient


def inline_figures(nb) -> int:
    """Number of image/png outputs of the executed notebook's code cells."""
    return sum("image/png" in out.get("data", {})
               for cell in nb.cells if cell.cell_type == "code" for out in cell.get("outputs", []))


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    path, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": work}})
    try:
        client.execute()
    finally:
        name = os.path.splitext(os.path.basename(path))[0]
        nbformat.write(nb, os.path.join(work, name + ".executed.ipynb"))
    figures = inline_figures(nb)
    if figures == 0:
        print(f"notebook {os.path.basename(path)}: no inline figure (image/png output); "
              "use '%matplotlib inline' and show the plots", file=sys.stderr)
        return 1
    print(f"notebook {os.path.basename(path)}: all cells ran, {figures} inline figure(s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
