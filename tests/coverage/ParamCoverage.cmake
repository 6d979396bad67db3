# The parameter-coverage check, run by ctest after every other entry (fixture clean-up):
#   cmake -DCTEST=<ctest> -DBUILD_DIR=<build> -DCHECKER=<fascia-param-coverage> -DLOG=<log>
#         -DALLOW=<ParamAllowList.txt> -P ParamCoverage.cmake
# Writes the names of the entries a complete run has (all that `ctest -N` lists but the log's own
# set-up and this check) next to the log, then runs the checker on the log (see README.md).
include(${CMAKE_CURRENT_LIST_DIR}/TestLists.cmake)
foreach(var CTEST BUILD_DIR CHECKER LOG ALLOW)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "ParamCoverage.cmake: -D${var}=... is required")
  endif()
endforeach()
# coverage is judged on the full build: without VTK, the tests that need it (and what only they
# exercise) are not built
if(DEFINED WITH_VTK AND NOT WITH_VTK)
  message("param-coverage: skipped: a build without VTK has not every test (the coverage is judged on the full build)")
  return()
endif()
fascia_ctest_names(names)
set(text "")
foreach(name IN LISTS names)
  if(NOT name STREQUAL "param_coverage" AND NOT name STREQUAL "param_log_reset")
    fascia_unescape(n "${name}")
    string(APPEND text "${n}\n")
  endif()
endforeach()
file(WRITE "${LOG}.tests" "${text}")
if(NOT EXISTS "${LOG}")
  file(TOUCH "${LOG}")
endif()
execute_process(COMMAND "${CHECKER}" --log "${LOG}" --allow "${ALLOW}" --tests "${LOG}.tests" RESULT_VARIABLE rc)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "param_coverage failed (see the list above)")
endif()
