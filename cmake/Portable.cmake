# Flags and helpers for portable code (firmware/, hal/ outside hal/fake).
# On the host the portable sources are built as C++17 with no C++ standard library headers
# (-nostdinc++), no exceptions and no RTTI, warnings as errors; the dialect that XC16++
# (GCC 4.5) accepts is checked by tools/dialect_check, run from ctest.

if(ENGRAVER_PLATFORM STREQUAL "host")
  set(ENGRAVER_PORTABLE_FLAGS
      -nostdinc++ -fno-exceptions -fno-rtti
      -Wall -Wextra -Wshadow -Wcast-align -Wnon-virtual-dtor -Werror)
elseif(ENGRAVER_PLATFORM STREQUAL "avr")
  set(ENGRAVER_PORTABLE_FLAGS -std=gnu++11 -fno-exceptions -fno-rtti -fno-threadsafe-statics
      -Wall -Wextra -Werror -Wno-error=type-limits)
else()
  set(ENGRAVER_PORTABLE_FLAGS -std=gnu++0x -fno-exceptions -fno-rtti -Wall)
endif()

# engraver_portable_library(name [STATIC|INTERFACE] sources...)
# A library of portable code: include root is the repository top, so includes name their
# full path ("firmware/core/isqrt.h", "hal/interfaces/spi_master.h").
function(engraver_portable_library name)
  if(ARGV1 STREQUAL "INTERFACE")
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${PROJECT_SOURCE_DIR})
    return()
  endif()
  add_library(${name} STATIC ${ARGN})
  # Listed for the AVR proxy's size report (host_tests/target_proxy).
  set_property(GLOBAL APPEND PROPERTY ENGRAVER_PORTABLE_LIBRARIES ${name})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_compile_options(${name} PRIVATE ${ENGRAVER_PORTABLE_FLAGS})
  if(ENGRAVER_PLATFORM STREQUAL "host")
    set_target_properties(${name} PROPERTIES CXX_EXTENSIONS OFF)
  endif()
endfunction()

# add_subdirectory for each listed folder.
function(engraver_add_parts)
  foreach(part ${ARGN})
    add_subdirectory(${part})
  endforeach()
endfunction()

# engraver_size_over_speed(TARGETS target... | SOURCES file...): code that runs at start-up,
# per frame or per queue item (not the per-point stepping, the 1 ms tick, the
# planner or the path controller) built without loop-invariant motion on the targets (XC16
# and the AVR proxy): the addresses and values hoisted out of a loop and held across it
# cost more code than the loop saves (-0.2 kB on the AVR image, docs/performance.md).
# Host builds unchanged.
# A plain variable, not a cache entry: a build tree configured before keeps a cache entry's
# old value, so a changed list here would not reach it (the ratchet would fail there).
set(ENGRAVER_SIZE_OVER_SPEED_FLAGS
    "-fno-move-loop-invariants -fno-optimize-sibling-calls -fno-tree-dominator-opts -fno-jump-tables -fno-tree-copy-prop -fno-tree-loop-ivcanon -fno-forward-propagate -fno-tree-vrp -fno-ipa-sra -fno-tree-loop-im")
function(engraver_size_over_speed kind)
  if(ENGRAVER_PLATFORM STREQUAL "host")
    return()
  endif()
  separate_arguments(flags UNIX_COMMAND "${ENGRAVER_SIZE_OVER_SPEED_FLAGS}")
  if(kind STREQUAL "TARGETS")
    foreach(name ${ARGN})
      target_compile_options(${name} PRIVATE ${flags})
    endforeach()
  else()
    set_source_files_properties(${ARGN} PROPERTIES COMPILE_OPTIONS "${flags}")
  endif()
endfunction()
