# Runs one script test (registered with fascia_add_script_test, cmake/FasciaTesting.cmake):
#   cmake -DFASCIA_TEST_NAME=<ctest name> -DFASCIA_PARAM_LOG=<log> -P RunMarked.cmake -- <command...>
# First appends "ran<TAB><name>" to the parameter-coverage log (what tests/catch_main.cpp does for
# the Catch2 cases), so that param_coverage knows the run was complete; then runs the command,
# its output passing through, and fails when it exits with anything but 0.
set(_cmd "")
set(_after FALSE)
math(EXPR _last "${CMAKE_ARGC} - 1")
foreach(i RANGE ${_last})
  if(_after)
    list(APPEND _cmd "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(_after TRUE)
  endif()
endforeach()
if(NOT _cmd OR NOT DEFINED FASCIA_TEST_NAME OR NOT DEFINED FASCIA_PARAM_LOG)
  message(FATAL_ERROR "usage: cmake -DFASCIA_TEST_NAME=.. -DFASCIA_PARAM_LOG=.. -P RunMarked.cmake -- command...")
endif()
file(APPEND "${FASCIA_PARAM_LOG}" "ran\t${FASCIA_TEST_NAME}\n")
execute_process(COMMAND ${_cmd} RESULT_VARIABLE rc)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "${FASCIA_TEST_NAME}: exited with '${rc}'")
endif()
