# Checks that `ctest -N` lists exactly the Catch2 test cases of every test executable (their
# --list-test-names-only) plus the script tests, no more, no fewer:
#   cmake -DCTEST=<ctest> -DBUILD_DIR=<build> -DLISTS=<build>/Testing/fascia-test-lists.txt -P CheckCtestList.cmake
# LISTS (written by tests/CMakeLists.txt) has "catch <executable>" and "script <ctest name>" lines.
# An entry ctest has and no case matches (half of a name split at a ';', a test added with a bare
# add_test instead of fascia_add_script_test) and a case ctest lacks both fail, named.
include(${CMAKE_CURRENT_LIST_DIR}/TestLists.cmake)
foreach(var CTEST BUILD_DIR LISTS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "CheckCtestList.cmake: -D${var}=... is required")
  endif()
endforeach()

file(READ "${LISTS}" text)
fascia_lines(lists "${text}")
set(expected "")
set(nExecutables 0)
foreach(line IN LISTS lists)
  if(line MATCHES "^catch (.*)$")
    fascia_unescape(exe "${CMAKE_MATCH_1}")
    execute_process(COMMAND "${exe}" --list-test-names-only WORKING_DIRECTORY "${BUILD_DIR}"
                    OUTPUT_VARIABLE cases RESULT_VARIABLE rc)
    if(rc MATCHES "[^0-9]")
      message(FATAL_ERROR "${exe} --list-test-names-only failed: ${rc}")
    endif()
    fascia_lines(names "${cases}")
    list(LENGTH names n)
    if(n EQUAL 0)
      message(SEND_ERROR "${exe} has no test case")
    endif()
    list(APPEND expected ${names})
    math(EXPR nExecutables "${nExecutables} + 1")
  elseif(line MATCHES "^script (.*)$")
    list(APPEND expected "${CMAKE_MATCH_1}")
  endif()
endforeach()

fascia_ctest_names(actual)

# multiset difference, both ways
set(extra ${actual})
set(missing "")
foreach(name IN LISTS expected)
  list(FIND extra "${name}" at)
  if(at EQUAL -1)
    list(APPEND missing "${name}")
  else()
    list(REMOVE_AT extra ${at})
  endif()
endforeach()

list(LENGTH actual nActual)
list(LENGTH expected nExpected)
set(report "")
foreach(name IN LISTS extra)
  fascia_unescape(n "${name}")
  string(APPEND report "  ctest lists '${n}', which is no Catch2 case and no script test\n")
endforeach()
foreach(name IN LISTS missing)
  fascia_unescape(n "${name}")
  string(APPEND report "  the case '${n}' has no ctest entry of its own (a ';' in its name splits it?)\n")
endforeach()
if(report)
  message(FATAL_ERROR "ctest lists ${nActual} entries, the ${nExecutables} Catch2 executables and the script "
                      "tests have ${nExpected}:\n${report}")
endif()
message(STATUS "ctest lists exactly the ${nExpected} cases of ${nExecutables} Catch2 executables and the script tests")
