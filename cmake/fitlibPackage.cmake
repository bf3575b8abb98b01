# Installation and the CMake / pkg-config package: `cmake --install build --prefix P`, then
# find_package(fitlib) gives fitlib::fitlib (all modules) and fitlib::<module>.
include(CMakePackageConfigHelpers)

set(FITLIB_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/fitlib)
set(FITLIB_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/fitlib)
set(FITLIB_INSTALLED_TARGETS fitlib)
foreach(module ${FITLIB_BUILT_MODULES})
  list(APPEND FITLIB_INSTALLED_TARGETS fitlib_${module})
endforeach()

install(TARGETS ${FITLIB_INSTALLED_TARGETS} EXPORT fitlibTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS fitcli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET fitcli-mpi)
  install(TARGETS fitcli-mpi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY fitlib/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY datasets docs DESTINATION ${FITLIB_INSTALL_DATADIR})
install(FILES README.md DESTINATION ${FITLIB_INSTALL_DATADIR})
install(EXPORT fitlibTargets NAMESPACE fitlib:: DESTINATION ${FITLIB_CMAKE_DIR})

configure_package_config_file(cmake/fitlibConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/fitlibConfig.cmake INSTALL_DESTINATION ${FITLIB_CMAKE_DIR}
  PATH_VARS FITLIB_INSTALL_DATADIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/fitlibConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/fitlibConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/fitlibConfigVersion.cmake DESTINATION ${FITLIB_CMAKE_DIR})

# pkg-config: modules from the top of the dependency order down, then what they link.
set(FITLIB_PC_LIBS "")
foreach(module scene fatigue segment belt surface card fit model data core)
  if(TARGET fitlib_${module})
    string(APPEND FITLIB_PC_LIBS " -lfitlib_${module}")
  endif()
endforeach()
# The prefix is found from the .pc file's own place, so the installed tree can be moved.
file(RELATIVE_PATH FITLIB_PC_TO_PREFIX /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
configure_file(cmake/fitlib.pc.in ${CMAKE_CURRENT_BINARY_DIR}/fitlib.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/fitlib.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

if(FITLIB_TESTS)
  # Installs this build into a fresh prefix and builds a small consumer against it, once through
  # find_package(fitlib) and once through pkg-config.
  add_test(NAME package_consumer
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tests/package/run.sh ${CMAKE_CURRENT_BINARY_DIR}
            ${CMAKE_CURRENT_SOURCE_DIR}/tests/package/consumer)
  set_tests_properties(package_consumer PROPERTIES LABELS package TIMEOUT 600)
endif()

# The man page (help2man from fitcli's own --help and --version, Debian help2man) and the bash
# completion (scripts/fitcli-completion.bash, which reads --help too), docs/cli.md.
install(FILES scripts/fitcli-completion.bash DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
  RENAME fitcli)
find_program(HELP2MAN help2man)
if(HELP2MAN)
  # Its SUBCOMMANDS section: every subcommand's own --help (scripts/fitcli-man-subcommands.sh).
  add_custom_command(OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/fitcli-subcommands.h2m
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/fitcli-man-subcommands.sh $<TARGET_FILE:fitcli>
            ${CMAKE_CURRENT_BINARY_DIR}/fitcli-subcommands.h2m
    DEPENDS fitcli ${CMAKE_CURRENT_SOURCE_DIR}/scripts/fitcli-man-subcommands.sh VERBATIM)
  add_custom_command(OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/fitcli.1
    COMMAND ${HELP2MAN} --no-info --no-discard-stderr --name "fit elastomer models to dynamic tests, write material cards, run belt scenes"
            --include ${CMAKE_CURRENT_BINARY_DIR}/fitcli-subcommands.h2m
            --output ${CMAKE_CURRENT_BINARY_DIR}/fitcli.1 $<TARGET_FILE:fitcli>
    DEPENDS fitcli ${CMAKE_CURRENT_BINARY_DIR}/fitcli-subcommands.h2m VERBATIM)
  add_custom_target(fitcli_man ALL DEPENDS ${CMAKE_CURRENT_BINARY_DIR}/fitcli.1)
  install(FILES ${CMAKE_CURRENT_BINARY_DIR}/fitcli.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
else()
  message(STATUS "help2man not found: no fitcli man page (scripts/install-deps.sh installs it)")
endif()
if(FITLIB_TESTS)
  add_test(NAME cli_completion_and_man
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tests/package/completion.sh $<TARGET_FILE:fitcli>
            ${CMAKE_CURRENT_SOURCE_DIR}/scripts/fitcli-completion.bash ${CMAKE_CURRENT_BINARY_DIR}/fitcli.1)
  set_tests_properties(cli_completion_and_man PROPERTIES LABELS package TIMEOUT 120)
endif()
