# Helpers shared by CheckCtestList.cmake and ParamCoverage.cmake.

# fascia_lines(<out> <text>): the non-empty lines of text as a CMake list. The characters CMake lists
# treat specially (\ ; [ ]) are kept as <bs> <sc> <lb> <rb>, so that a test name holding one stays
# one element; fascia_unescape() turns them back for messages.
function(fascia_lines out text)
  string(REPLACE "\\" "<bs>" text "${text}")
  string(REPLACE ";" "<sc>" text "${text}")
  string(REPLACE "[" "<lb>" text "${text}")
  string(REPLACE "]" "<rb>" text "${text}")
  string(REPLACE "\r" "" text "${text}")
  string(REPLACE "\n" ";" text "${text}")
  set(result "")
  foreach(line IN LISTS text)
    if(NOT line STREQUAL "")
      list(APPEND result "${line}")
    endif()
  endforeach()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

function(fascia_unescape out text)
  string(REPLACE "<sc>" ";" text "${text}")
  string(REPLACE "<lb>" "[" text "${text}")
  string(REPLACE "<rb>" "]" text "${text}")
  string(REPLACE "<bs>" "\\" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# fascia_ctest_names(<out>): the names of the entries `ctest -N` lists in BUILD_DIR (escaped).
function(fascia_ctest_names out)
  execute_process(COMMAND "${CTEST}" -N WORKING_DIRECTORY "${BUILD_DIR}"
                  OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "ctest -N failed (${rc}):\n${text}")
  endif()
  fascia_lines(lines "${text}")
  set(names "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^ *Test +#[0-9]+: (.*)$")
      list(APPEND names "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  set(${out} "${names}" PARENT_SCOPE)
endfunction()
