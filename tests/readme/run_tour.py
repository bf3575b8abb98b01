#!/usr/bin/env python3
"""Runs the README's shell examples as printed (issue 37: the tour cannot drift from the code).

Usage: run_tour.py SOURCE_DIR BUILD_DIR. Every ```sh block of the sections "A five-minute tour" and
"More examples" (under "Command line") runs in a fresh folder holding a link to datasets/, with
BUILD_DIR first on PATH, one command at a time (continued lines and here-documents joined). A
command whose comment says "exit N" must exit N, every other one 0. mpirun lines are skipped (the
MPI test runs them). Prints each command with its exit code and time; exits 1 on the first miss.
"""
import os
import re
import subprocess
import sys
import tempfile
import time


def blocks(readme, start, stop):
    text = readme[readme.index(start):]
    text = text[:text.index(stop)] if stop in text else text
    return re.findall(r"```sh\n(.*?)```", text, re.S)


def commands(block):
    lines = block.split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        i += 1
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        command = line
        heredoc = re.search(r"<<'?(\w+)'?", line)
        if heredoc:
            while i < len(lines) and lines[i] != heredoc.group(1):
                command += "\n" + lines[i]
                i += 1
            command += "\n" + heredoc.group(1)
            i += 1
        while command.rstrip().endswith("\\") and i < len(lines):
            command = command.rstrip()[:-1] + " " + lines[i].strip()
            i += 1
        yield command


def expected_exit(command):
    m = re.search(r"#.*\bexit (\d+)", command)
    return int(m.group(1)) if m else 0


def main():
    source, build = sys.argv[1], sys.argv[2]
    readme = open(os.path.join(source, "README.md"), encoding="utf-8").read()
    chosen = blocks(readme, "## A five-minute tour", "## Where outputs land")
    chosen += blocks(readme, "More examples", "## Accuracy knobs")
    env = dict(os.environ, PATH=build + os.pathsep + os.environ.get("PATH", ""))
    with tempfile.TemporaryDirectory(prefix="fitlib-tour-") as work:
        os.symlink(os.path.join(source, "datasets"), os.path.join(work, "datasets"))
        os.makedirs(os.path.join(work, "out"))
        count = 0
        for block in chosen:
            for command in commands(block):
                if command.lstrip().startswith("mpirun"):
                    continue
                want = expected_exit(command)
                t0 = time.time()
                r = subprocess.run(["bash", "-c", command], cwd=work, env=env, capture_output=True, text=True)
                count += 1
                print(f"[{r.returncode}] {time.time() - t0:6.2f} s  {command.splitlines()[0][:110]}")
                if r.returncode != want:
                    print(f"expected exit {want}; stderr:\n{r.stderr[-2000:]}")
                    return 1
        print(f"{count} README commands ran as printed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
