# Compile options shared by Fascia and by plugins built against it.
if(NOT TARGET fascia_flags)
  add_library(fascia_flags INTERFACE)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(fascia_flags INTERFACE
      $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wno-unused-parameter>
      # GCC with -std=c++17 disables contraction; contraction (FMA) matters in the element loops: docs/performance.md, lesson 8
      $<$<COMPILE_LANGUAGE:CXX>:-ffp-contract=fast>)
    if(FASCIA_NATIVE)
      target_compile_options(fascia_flags INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-march=native>)
    endif()
  endif()
endif()
