# Included by the top-level CMakeLists.txt before any library when BALLBOX_FUZZ=ON: every object is
# built with libFuzzer's coverage hooks and AddressSanitizer + UndefinedBehaviorSanitizer, and any
# sanitizer report stops the fuzzer (no recovery), so it counts as a crash.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(WARNING "BALLBOX_FUZZ needs clang (libFuzzer); configure with CXX=clang++ CC=clang. "
                  "The fuzz targets are not built.")
  set(BALLBOX_FUZZ_ACTIVE OFF)
  return()
endif()
set(BALLBOX_FUZZ_ACTIVE ON)
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                    -fno-omit-frame-pointer -g)
add_link_options(-fsanitize=address,undefined)
