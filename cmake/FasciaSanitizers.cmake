# Sanitizer builds (docs/robustness.md). Global flags, so that the core, every plugin, the tests and
# the fuzz targets are all instrumented alike.
#   FASCIA_SANITIZE=ON  ASan + UBSan (gcc or clang), -fno-sanitize-recover: the first report aborts
#   FASCIA_FUZZ=ON      the same, with libFuzzer's coverage instrumentation (clang only); the fuzz
#                       executables add -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt)
if(FASCIA_FUZZ AND NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "FASCIA_FUZZ=ON needs clang (libFuzzer), and the compiler is "
                      "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER}: configure a fresh build folder with "
                      "-DCMAKE_CXX_COMPILER=clang++ (or run `make fuzz`)")
endif()
if(FASCIA_FUZZ OR FASCIA_SANITIZE)
  set(_fascia_san -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options("$<$<COMPILE_LANGUAGE:CXX>:${_fascia_san}>")
  add_link_options(-fsanitize=address,undefined)
  if(FASCIA_FUZZ)
    add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-fsanitize=fuzzer-no-link>)
  endif()
endif()
