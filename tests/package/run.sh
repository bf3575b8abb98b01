#!/usr/bin/env bash
# Installs the build tree BUILD into a fresh prefix, then builds and runs the consumer project
# against it through find_package(fitlib) and through pkg-config. Prints what the consumer printed.
set -euo pipefail
build=$1
consumer=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/fitlib-package-XXXXXX")
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$consumer" -B "$work/cmake-build" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/cmake-build" >/dev/null
cmake_out=$("$work/cmake-build/consumer")
echo "find_package consumer: $cmake_out"
export PKG_CONFIG_PATH=$(dirname "$(find "$work/prefix" -name fitlib.pc)")
# shellcheck disable=SC2046
g++ -std=c++17 "$consumer/main.cpp" -DFITLIB_DATA_DIR="\"$work/prefix/share/fitlib\"" \
  $(pkg-config --cflags --libs fitlib) -o "$work/pc-consumer"
pc_out=$("$work/pc-consumer")
echo "pkg-config consumer: $pc_out"
# The Python module, when built, imports from the installed prefix alone (docs/python.md).
package=$(find "$work/prefix" -name '_fitlib*.so' -printf '%h\n' | head -1)
if [ -n "$package" ]; then
  py_out=$(cd "$work" && PYTHONPATH=$(dirname "$package") /usr/bin/python3 -c \
    'import fitlib; print(fitlib.__file__, len(fitlib.model_kinds()), "models")')
  echo "python module: $py_out"
  case "$py_out" in "$work/prefix/"*) ;; *) exit 1 ;; esac
fi
[ "$cmake_out" = "$pc_out" ]
