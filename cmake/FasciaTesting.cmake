# fascia_add_test(NAME <name> SOURCES <files...> [LIBS <targets...>] [PROPERTIES <name value...>])
#   One Catch2 executable in build/bin/tests, its test cases registered one by one with ctest
#   (PROPERTIES: more ctest properties of every case, e.g. SKIP_RETURN_CODE 77 for a case that
#   exits 77 where it cannot run, so that ctest reports it skipped, never passed).
# fascia_add_script_test(NAME <name> COMMAND <command...> [PROPERTIES <name value...>])
#   One ctest entry that is no Catch2 case (a CMake script, a shell script, a program).
#
# Every entry gets the two things the suite's own checks (tests/coverage/README.md) need:
# - FASCIA_PARAM_LOG in its environment, so the core logs the parameters it exercises, and a "ran"
#   line per entry (written by tests/catch_main.cpp, or by RunMarked.cmake for script tests);
# - the fixture fascia_param_log, so that param_log_reset runs before it and param_coverage after.
# Each Catch2 case runs with -w NoTests (a filter that matches no case fails instead of passing);
# tests/catch_main.cpp turns on NoAssertions (a case, or a leaf section, that checks nothing fails).
include(Catch)
if(NOT TARGET fascia_catch_main)
  add_library(fascia_catch_main STATIC ${PROJECT_SOURCE_DIR}/tests/catch_main.cpp)
  target_link_libraries(fascia_catch_main PUBLIC Catch2::Catch2 PRIVATE fascia_core)
endif()
set(FASCIA_PARAM_LOG_FILE ${PROJECT_BINARY_DIR}/Testing/param-coverage.log)
# the Catch2 executables and the script tests, for the check that ctest lists exactly them
set_property(GLOBAL PROPERTY FASCIA_CATCH_TESTS "")
set_property(GLOBAL PROPERTY FASCIA_SCRIPT_TESTS "")

# a test's time limit: the sanitizer build runs some 5 to 10 times slower (the Hertz test: over 300 s)
if(FASCIA_SANITIZE)
  set(FASCIA_TEST_TIMEOUT 1800)
else()
  set(FASCIA_TEST_TIMEOUT 300)
endif()

function(fascia_add_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS;PROPERTIES" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE fascia_catch_main fascia_core fascia_flags ${T_LIBS})
  target_compile_definitions(${T_NAME} PRIVATE
    FASCIA_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    FASCIA_BINARY_DIR="${PROJECT_BINARY_DIR}")
  set_target_properties(${T_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bin/tests)
  catch_discover_tests(${T_NAME} WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
                       EXTRA_ARGS -w NoTests
                       PROPERTIES TIMEOUT ${FASCIA_TEST_TIMEOUT}
                                  ENVIRONMENT "FASCIA_PARAM_LOG=${PROJECT_BINARY_DIR}/Testing/param-coverage.log"
                                  FIXTURES_REQUIRED fascia_param_log
                                  ${T_PROPERTIES})
  set_property(GLOBAL APPEND PROPERTY FASCIA_CATCH_TESTS $<TARGET_FILE:${T_NAME}>)
endfunction()

function(fascia_add_script_test)
  cmake_parse_arguments(T "" "NAME" "COMMAND;PROPERTIES" ${ARGN})
  set(_log ${PROJECT_BINARY_DIR}/Testing/param-coverage.log)
  add_test(NAME ${T_NAME}
           COMMAND ${CMAKE_COMMAND} -DFASCIA_TEST_NAME=${T_NAME} -DFASCIA_PARAM_LOG=${_log}
                   -P ${PROJECT_SOURCE_DIR}/tests/coverage/RunMarked.cmake -- ${T_COMMAND})
  set_tests_properties(${T_NAME} PROPERTIES ENVIRONMENT "FASCIA_PARAM_LOG=${_log}"
                                            FIXTURES_REQUIRED fascia_param_log ${T_PROPERTIES})
  set_property(GLOBAL APPEND PROPERTY FASCIA_SCRIPT_TESTS ${T_NAME})
endfunction()
