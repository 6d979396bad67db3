# Fails when a library's machine code holds no prefetch instruction: GCC 12 once deleted every
# prefetch of TLED's element loop (a loop of __builtin_prefetch alone, inlined into a large caller,
# counts as a loop without side effects), which made the viscous step 1.15-1.38 times slower with
# every test passing (docs/performance.md, lesson 11). Usage:
#   cmake -DOBJDUMP=... -DLIBRARY=... -P CheckPrefetch.cmake
execute_process(COMMAND ${OBJDUMP} -d ${LIBRARY} OUTPUT_VARIABLE _asm RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "objdump -d ${LIBRARY} failed (${_rc})")
endif()
string(REGEX MATCHALL "prefetcht0" _hits "${_asm}")
list(LENGTH _hits _n)
if(_n EQUAL 0)
  message(FATAL_ERROR "${LIBRARY}: no prefetcht0 instruction: the element loop's prefetches were compiled away")
endif()
message(STATUS "${LIBRARY}: ${_n} prefetcht0 instructions")
