#!/usr/bin/env bash
# `pip install .` from the source tree (pyproject.toml, setup.py) into a fresh folder, with the
# extension of the build tree BUILD (FITLIB_BUILD_DIR), then imports it from there alone.
set -euo pipefail
source=$1
build=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/fitlib-pip-XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir "$work/src"  # pip builds in the folder it is given: a copy, so no build/ lands in the source tree
cp "$source/pyproject.toml" "$source/setup.py" "$source/README.md" "$work/src/"
FITLIB_BUILD_DIR=$build /usr/bin/python3 -m pip install --quiet --no-build-isolation --no-deps --no-index \
  --target "$work/site" "$work/src"
out=$(cd "$work" && PYTHONPATH="$work/site" /usr/bin/python3 -c \
  'import fitlib; print(fitlib.__file__, fitlib.__version__, len(fitlib.model_kinds()), "models")')
echo "pip-installed module: $out"
case "$out" in "$work/site/fitlib/"*) ;; *) exit 1 ;; esac
