# Configures this tree with the host-fuzz preset in BIN and builds the fuzzers (the ctest
# fixture of the short fuzz runs). Usage: cmake -DSRC=<top> -DBIN=<dir> -P build_sub.cmake
find_program(CLANGXX NAMES clang++)
if(NOT CLANGXX)
  message("FUZZ-SKIPPED: clang++ not found")
  return()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --preset host-fuzz -B ${BIN}
                WORKING_DIRECTORY ${SRC} OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz sub-build: configure failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} --target engraver_fuzzers
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz sub-build failed (${rc})")
endif()
