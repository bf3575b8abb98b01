#!/bin/bash
# Link launcher of fitcli (CMakeLists.txt, FITLIB_STATIC_DEPS): runs the link command it is given
# with SuiteSparse, glog, gflags, freexl and LAPACK/BLAS/ATLAS taken from their static archives where
# one sits beside the shared library (Debian's -dev packages ship both), and the compiler's run-times
# those need (gfortran, quadmath, OpenMP) and libstdc++ from gcc's archives. Every shared library a
# process loads costs it the mapping, the symbol relocations and their page faults: 13 fewer
# libraries took about 3 ms off `fitcli fit --terms auto`, the next 8 about 4 ms more (docs/fitting.md
# "Speed", docs/decisions.md "fitcli start-up: the Ceres stack's libraries linked statically, ..." and
# "fitcli start-up: libstdc++, toml++ and LAPACK in the executable"). What the swapped libraries
# needed themselves (METIS, libunwind, ...) is added after them as shared libraries, only where the
# archives use it (--as-needed). The archive's code is the shared library's: nothing computed differs.
static_names=" libumfpack libamd libcamd libccolamd libcolamd libcholmod libspqr libsuitesparseconfig libcxsparse libglog libgflags libfreexl liblapack libblas libf77blas libatlas "
runtime_archives=" libgfortran libquadmath libgomp "  # gcc's own, found by the compiler driver
compiler=$1
args=()
needed=()
# The file the link would use for `-l:NAME` (the compiler driver searches the linker's path).
library_path() { local p; p=$("$compiler" -print-file-name="$1"); [[ $p == /* ]] && echo "$p"; }
# The static archive to link instead of shared library $1 (a path), if it is one of the above.
archive_of() {
  local real base
  real=$(readlink -f "$1")  # beside the library the symlink (or Debian alternative) names
  base=${real%%.so*}
  if [[ $static_names == *" ${base##*/} "* && -f $base.a ]]; then echo "$base.a"
  elif [[ $runtime_archives == *" ${base##*/} "* ]]; then library_path "${base##*/}.a"
  else return 1; fi
}
# What shared library $1 needs, as archives where there are (and then what those need), else shared.
add_needed() {
  local lib path archive
  while read -r lib; do  # the C and C++ run-times stay the compiler driver's
    [[ $lib == libc.so* || $lib == libm.so* || $lib == ld-linux* || $lib == libstdc++* || $lib == libgcc_s* ]] && continue
    if path=$(library_path "$lib") && archive=$(archive_of "$path"); then
      [[ " ${needed[*]} " == *" $archive "* ]] && continue
      needed+=("$archive")
      add_needed "$path"
    elif [[ " ${needed[*]} " != *" -l:$lib "* ]]; then
      needed+=("-l:$lib")
    fi
  done < <(readelf -d "$1" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
}
for a in "$@"; do
  if [[ ($a == /*.so || $a == /*.so.*) ]] && archive=$(archive_of "$a"); then
    add_needed "$a"
    a=$archive
  fi
  # toml++ compiled into fitcli (fitcli/tomlplusplus.cpp, CMakeLists.txt): its shared library, the
  # last one that needs libstdc++.so, is not linked.
  [[ $a == */libtomlplusplus.so* && " $* " == *"/tomlplusplus.cpp.o "* ]] && continue
  args+=("$a")
done
# libgcc_s ahead of them: libunwind (glog's) defines _Unwind_* too, and exceptions must unwind
# through the compiler's run-time as before, which binds the symbols of the library loaded first.
[[ ${#needed[@]} -gt 0 ]] && args+=(-Wl,--as-needed -lgcc_s "${needed[@]}")
# libstdc++ from its archive when no shared library left on the line needs libstdc++.so (two copies
# of the C++ run-time in one process would not share exceptions, locales or the heap's operator new)
# and no sanitizer is linked (it replaces operator new and delete from its own shared library).
uses_shared_cxx_runtime() {
  local a path
  for a in "${args[@]}"; do
    case $a in
      -fsanitize=*) return 0 ;;
      -l:*.so*) path=$(library_path "${a#-l:}") || continue ;;
      /*.so | /*.so.*) path=$a ;;
      *) continue ;;
    esac
    readelf -d "$path" | grep -q 'NEEDED.*\[libstdc++' && return 0
  done
  return 1
}
uses_shared_cxx_runtime || args+=(-static-libstdc++)
exec "${args[@]}"
