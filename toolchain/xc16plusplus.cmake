# Toolchain for the real target: dsPIC30F6014 with Microchip XC16 plus XC16++ (the public
# g++ patches for XC16's GCC 4.5.1: xc16-g++ -> xc16-gcc driving elf-cc1plus).
#   cmake --preset dspic -DENGRAVER_XC16_DIR=/opt/microchip/xc16/v2.10
#   cmake --build --preset dspic
# XC16 is proprietary and not a Debian package: this file cannot be exercised in CI. The
# dialect check and the AVR proxy build (toolchain/avr-simavr.cmake) stand in for it there.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR dspic30f)

set(ENGRAVER_XC16_DIR "/opt/microchip/xc16/v2.10" CACHE PATH
    "XC16 install folder, with the XC16++ files added to bin/ and bin/bin/")
set(ENGRAVER_XC16_CPU "30F6014" CACHE STRING "-mcpu= part name")
set(ENGRAVER_XC16_HEAP_BYTES "0" CACHE STRING "heap size (the firmware uses no heap)")

find_program(ENGRAVER_XC16_GCC xc16-gcc HINTS ${ENGRAVER_XC16_DIR}/bin NO_DEFAULT_PATH)
find_program(ENGRAVER_XC16_GXX xc16-g++ HINTS ${ENGRAVER_XC16_DIR}/bin NO_DEFAULT_PATH)
if(NOT ENGRAVER_XC16_GCC OR NOT ENGRAVER_XC16_GXX)
  message(FATAL_ERROR
    "XC16 with XC16++ not found in ${ENGRAVER_XC16_DIR}: need bin/xc16-gcc and bin/xc16-g++ "
    "(the XC16++ symlink to xc16-gcc) plus bin/bin/elf-cc1plus and elf-g++. "
    "Set -DENGRAVER_XC16_DIR=... See docs/toolchain.md.")
endif()
find_program(ENGRAVER_XC16_BIN2HEX xc16-bin2hex HINTS ${ENGRAVER_XC16_DIR}/bin NO_DEFAULT_PATH)
find_program(CMAKE_AR xc16-ar HINTS ${ENGRAVER_XC16_DIR}/bin NO_DEFAULT_PATH)
find_program(CMAKE_OBJCOPY xc16-objcopy HINTS ${ENGRAVER_XC16_DIR}/bin NO_DEFAULT_PATH)

# XC16's driver does not survive CMake's compiler identification runs; it is GCC 4.5.1.
set(CMAKE_C_COMPILER ${ENGRAVER_XC16_GCC})
set(CMAKE_CXX_COMPILER ${ENGRAVER_XC16_GXX})
set(CMAKE_C_COMPILER_FORCED TRUE)
set(CMAKE_CXX_COMPILER_FORCED TRUE)
set(CMAKE_C_COMPILER_ID GNU)
set(CMAKE_CXX_COMPILER_ID GNU)
set(CMAKE_C_COMPILER_VERSION 4.5.1)
set(CMAKE_CXX_COMPILER_VERSION 4.5.1)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# The device's linker script, from the XC16 support tree.
find_file(ENGRAVER_XC16_LINKER_SCRIPT p${ENGRAVER_XC16_CPU}.gld
          HINTS ${ENGRAVER_XC16_DIR}/support/dsPIC30F/gld NO_DEFAULT_PATH)
if(NOT ENGRAVER_XC16_LINKER_SCRIPT)
  set(ENGRAVER_XC16_LINKER_SCRIPT p${ENGRAVER_XC16_CPU}.gld)  # the driver's search path
endif()

# gnu++0x is all GCC 4.5 knows; no C++ library, so no exceptions, RTTI or guarded statics.
# -no-legacy-libc: XC16++ does not support the legacy C library (the default since 1.25).
# __bool_true_and_false_are_defined keeps XC16's stdbool.h away from C++'s bool.
set(CMAKE_C_FLAGS_INIT "-mcpu=${ENGRAVER_XC16_CPU} -omf=elf -no-legacy-libc")
set(CMAKE_CXX_FLAGS_INIT
    "-mcpu=${ENGRAVER_XC16_CPU} -omf=elf -no-legacy-libc -std=gnu++0x -fno-exceptions -fno-rtti -fno-threadsafe-statics -D__bool_true_and_false_are_defined -ffunction-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-mcpu=${ENGRAVER_XC16_CPU} -omf=elf -no-legacy-libc -Wl,--script=${ENGRAVER_XC16_LINKER_SCRIPT},--heap=${ENGRAVER_XC16_HEAP_BYTES},--gc-sections,--report-mem")
# The free XC16 licence allows -O0 and -O1 only; -Os/-O2 need a PRO licence.
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-O1")
set(CMAKE_CXX_FLAGS_MINSIZEREL_INIT "-O1")

set(CMAKE_FIND_ROOT_PATH ${ENGRAVER_XC16_DIR})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

set(ENGRAVER_PLATFORM "dspic" CACHE STRING "host, avr or dspic" FORCE)
