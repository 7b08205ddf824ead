# Short libFuzzer run for the normal test command: configure + build fuzz/ with clang in a
# sub-build, then run fuzz_protocol over the seed corpus for a fixed number of runs.
# Usage: cmake -DSRC=<repo top> -DBIN=<work dir> -DGEN=<generator> -DRUNS=<n> -P run_short.cmake
find_program(CLANGXX NAMES clang++ clang++-16 clang++-15 clang++-14)
if(NOT CLANGXX)
  message("FUZZ-SKIPPED: clang++ not found")
  return()
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SRC}/fuzz -B ${BIN} -G ${GEN} -DCMAKE_CXX_COMPILER=${CLANGXX}
          -DCMAKE_BUILD_TYPE=RelWithDebInfo
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz sub-build configure failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} --target fuzz_protocol RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz sub-build failed (${rc})")
endif()
# New inputs go to a scratch corpus; the checked-in seeds are only read.
file(REMOVE_RECURSE ${BIN}/corpus)
file(MAKE_DIRECTORY ${BIN}/corpus)
execute_process(
  COMMAND ${BIN}/fuzz_protocol -seed=1 -runs=${RUNS} -max_len=512 -print_final_stats=1
          -artifact_prefix=${BIN}/ ${BIN}/corpus ${SRC}/fuzz/corpus/protocol
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz_protocol found a failure (${rc}); reproducer in ${BIN}/")
endif()
