# CMake toolchain file: Windows x86-64 programs from Linux with MinGW-w64 (Debian's
# g++-mingw-w64-x86-64-posix), statically linked, so that a Windows machine runs them with nothing
# installed (docs/install.md, "Windows"):
#   cmake -S . -B build-windows -DCMAKE_TOOLCHAIN_FILE=cli/windows/mingw-w64.cmake
# The posix flavour of the compiler is the one whose C++ library has std::thread and std::mutex.
# With Wine installed, CTest runs the test programs through it (CMAKE_CROSSCOMPILING_EMULATOR).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(TMCL_MINGW_PREFIX x86_64-w64-mingw32)
set(CMAKE_C_COMPILER ${TMCL_MINGW_PREFIX}-gcc-posix)
set(CMAKE_CXX_COMPILER ${TMCL_MINGW_PREFIX}-g++-posix)
set(CMAKE_RC_COMPILER ${TMCL_MINGW_PREFIX}-windres)
set(CMAKE_FIND_ROOT_PATH /usr/${TMCL_MINGW_PREFIX})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
# Everything static: libgcc, libstdc++ and winpthread are in the .exe, no DLL beside it.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
find_program(TMCL_WINE NAMES wine wine64)
if(TMCL_WINE)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${TMCL_WINE})
endif()
