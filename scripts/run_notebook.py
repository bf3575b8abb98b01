#!/usr/bin/env python3
"""Runs a notebook headless (nbclient) in a work folder; fails if any cell raises.

usage: run_notebook.py NOTEBOOK.ipynb WORK_DIR
The executed copy is written to WORK_DIR/<name>.executed.ipynb for inspection; figures the
notebook saves land in WORK_DIR.
"""
import os
import sys

import nbformat
from nbclient import NotebookClient


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
    print(f"notebook {os.path.basename(path)}: all cells ran")
    return 0


if __name__ == "__main__":
    sys.exit(main())
