// toml++'s implementation compiled into fitcli (FITLIB_STATIC_DEPS; CMakeLists.txt), from the same
// headers (Debian's libtomlplusplus-dev) whose shared library the other targets link: fitcli then
// needs no shared library built on libstdc++.so and takes libstdc++ from its archive
// (cmake/link-static-deps.sh; docs/decisions.md "fitcli start-up: libstdc++, toml++ and LAPACK in
// the executable"). The flags are pkg-config's (TOML_HEADER_ONLY=0), so the symbols are the ones the
// fitlib archives' objects reference.
#define TOML_IMPLEMENTATION
#include <toml++/toml.h>
