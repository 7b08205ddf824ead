# Short libFuzzer run of fuzz_NAME in BIN over its seed corpus: RUNS executions, fixed seed,
# new inputs to a scratch corpus (the checked-in seeds are only read).
# Usage: cmake -DBIN=<dir> -DNAME=<n> -DRUNS=<n> -DMAX_LEN=<bytes> -DCORPUS=<dir>
#              [-DDICT=<file>] -P run_short.cmake
set(exe ${BIN}/fuzz_${NAME})
if(NOT EXISTS ${exe})
  message("FUZZ-SKIPPED: ${exe} was not built (no clang?)")
  return()
endif()
set(scratch ${BIN}/short-${NAME})
file(REMOVE_RECURSE ${scratch})
file(MAKE_DIRECTORY ${scratch}/corpus)
set(dict_arg "")
if(DICT)
  set(dict_arg -dict=${DICT})
endif()
execute_process(
  COMMAND ${exe} -seed=1 -runs=${RUNS} -max_len=${MAX_LEN} -timeout=2 -rss_limit_mb=2048
          -print_final_stats=1 ${dict_arg} -artifact_prefix=${scratch}/ ${scratch}/corpus
          ${CORPUS}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz_${NAME} found a failure (${rc}); reproducer in ${scratch}/")
endif()
