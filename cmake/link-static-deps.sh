#!/bin/bash
# Link launcher of fitcli (CMakeLists.txt, FITLIB_STATIC_DEPS): runs the link command it is given
# with SuiteSparse, glog, gflags and freexl taken from their static archives where one sits beside
# the shared library (Debian's -dev packages ship both). Every shared library a process loads costs
# it the mapping, the relocations and their page faults: 13 fewer libraries took about 3 ms off
# `fitcli fit --terms auto` (docs/fitting.md "Speed", docs/decisions.md "fitcli start-up: the
# Ceres stack's libraries linked statically, ..."). What the swapped libraries needed themselves
# (LAPACK, METIS, OpenMP, libunwind, ...) is added after them as shared libraries, only where the
# archives use it (--as-needed). The archive's code is the shared library's: nothing computed differs.
static_names=" libumfpack libamd libcamd libccolamd libcolamd libcholmod libspqr libsuitesparseconfig libcxsparse libglog libgflags libfreexl "
args=()
needed=()
for a in "$@"; do
  if [[ $a == /*.so || $a == /*.so.* ]]; then
    base=${a%%.so*}
    if [[ $static_names == *" ${base##*/} "* && -f $base.a ]]; then
      while read -r lib; do  # the C and C++ run-times stay the compiler driver's
        [[ $lib == libc.so* || $lib == libm.so* || $lib == ld-linux* || $lib == libstdc++* || $lib == libgcc_s* ||
           " ${needed[*]} " == *" -l:$lib "* ]] || needed+=("-l:$lib")
      done < <(readelf -d "$a" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
      a=$base.a
    fi
  fi
  args+=("$a")
done
# libgcc_s ahead of them: libunwind (glog's) defines _Unwind_* too, and exceptions must unwind
# through the compiler's run-time as before, which binds the symbols of the library loaded first.
[[ ${#needed[@]} -gt 0 ]] && args+=(-Wl,--as-needed -lgcc_s "${needed[@]}")
exec "${args[@]}"
