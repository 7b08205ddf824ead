# Short libFuzzer run of one PCB reader target (fuzz_gerber or fuzz_excellon) for ctest:
# configure + build fuzz/ with clang in a sub-build, then RUNS executions over the seeds.
# Usage: cmake -DSRC=<repo top> -DBIN=<work dir> -DGEN=<generator> -DNAME=<gerber|excellon>
#              -DRUNS=<n> -DMAX_LEN=<bytes> -P run_short_pcb.cmake
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
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} --target fuzz_${NAME} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz sub-build failed (${rc})")
endif()
set(scratch ${BIN}/short-${NAME})
file(REMOVE_RECURSE ${scratch})
file(MAKE_DIRECTORY ${scratch}/corpus)
execute_process(
  COMMAND ${BIN}/fuzz_${NAME} -seed=1 -runs=${RUNS} -max_len=${MAX_LEN} -timeout=10
          -rss_limit_mb=2048 -print_final_stats=1 -dict=${SRC}/fuzz/${NAME}.dict
          -artifact_prefix=${scratch}/ ${scratch}/corpus ${SRC}/fuzz/corpus/${NAME}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz_${NAME} found a failure (${rc}); reproducer in ${scratch}/")
endif()
