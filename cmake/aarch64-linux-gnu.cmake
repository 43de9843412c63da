# Cross-compiling for 64-bit ARM with Debian's g++-aarch64-linux-gnu; make test-arm64 runs the
# result under qemu-aarch64 (the emulator below lets CMake run what it builds, too).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)

# Libraries and headers from the arm64 tree only, tools from the host.
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
# Header-only libraries (nlohmann-json) are installed once for every architecture, in /usr/include
# and /usr/share/cmake: their package files are found there, and /usr/include is searched after
# the arm64 headers (-idirafter), so it can only supply what the arm64 tree lacks.
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
set(CMAKE_CXX_FLAGS_INIT "-idirafter /usr/include")
