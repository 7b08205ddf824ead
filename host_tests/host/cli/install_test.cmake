# Installs the build tree into a scratch prefix and runs the installed tool: the install
# rule puts `engraver` in PREFIX/bin and the copy works on its own.
# Run as: cmake -DBUILD_DIR=... -DPREFIX=... -P install_test.cmake
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${out}${err}")
endif()
if(NOT EXISTS "${PREFIX}/bin/engraver")
  message(FATAL_ERROR "no ${PREFIX}/bin/engraver after cmake --install: ${out}")
endif()
execute_process(COMMAND "${PREFIX}/bin/engraver" --version
                RESULT_VARIABLE rc OUTPUT_VARIABLE version)
if(NOT rc EQUAL 0 OR NOT version MATCHES "^engraver ")
  message(FATAL_ERROR "installed engraver --version: ${rc} '${version}'")
endif()
file(REMOVE_RECURSE "${PREFIX}")
