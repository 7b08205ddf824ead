# Toolchain for the 16-bit proxy: avr-g++ (Debian gcc-avr, GCC 5.4) for an ATmega2560, run
# in simavr. 16-bit int, 32-bit double, 8 KB RAM like the dsPIC30F6014, and no C++ library,
# so the portable tree is proven on a target as poor as the real one.
#   cmake --preset avr-proxy && cmake --build --preset avr-proxy
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR avr)

find_program(ENGRAVER_AVR_GCC avr-gcc REQUIRED DOC "avr-gcc (Debian package gcc-avr)")
find_program(ENGRAVER_AVR_GXX avr-g++ REQUIRED DOC "avr-g++ (Debian package gcc-avr)")
set(CMAKE_C_COMPILER ${ENGRAVER_AVR_GCC})
set(CMAKE_CXX_COMPILER ${ENGRAVER_AVR_GXX})
find_program(CMAKE_OBJCOPY avr-objcopy)
find_program(ENGRAVER_AVR_SIZE avr-size DOC "avr-size, for RAM/flash figures")

set(ENGRAVER_AVR_MCU "atmega2560" CACHE STRING "AVR part (8 KB RAM, like the dsPIC30F6014)")
set(ENGRAVER_AVR_F_CPU "16000000" CACHE STRING "AVR clock in Hz (simavr runs it at this rate)")

# Flags the portable code must survive: gnu++11 (closest avr-g++ has to XC16's gnu++0x), no
# exceptions, no RTTI, no thread-safe statics (no __cxa_guard_* on the target).
set(CMAKE_C_FLAGS_INIT "-mmcu=${ENGRAVER_AVR_MCU} -DF_CPU=${ENGRAVER_AVR_F_CPU}UL")
set(CMAKE_CXX_FLAGS_INIT
    "-mmcu=${ENGRAVER_AVR_MCU} -DF_CPU=${ENGRAVER_AVR_F_CPU}UL -std=gnu++11 -fno-exceptions -fno-rtti -fno-threadsafe-statics -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-mmcu=${ENGRAVER_AVR_MCU} -Wl,--gc-sections")

# Executables cannot run here; compiler checks build a static library instead.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

# The top-level CMakeLists builds only the portable libraries and the proxy test runner.
set(ENGRAVER_PLATFORM "avr" CACHE STRING "host, avr or dspic" FORCE)
