# fascia_add_test(NAME <name> SOURCES <files...> [LIBS <targets...>])
# One Catch2 executable in build/bin/tests, its test cases registered one by one with ctest.
include(Catch)
if(NOT TARGET fascia_catch_main)
  add_library(fascia_catch_main STATIC ${PROJECT_SOURCE_DIR}/tests/catch_main.cpp)
  target_link_libraries(fascia_catch_main PUBLIC Catch2::Catch2)
endif()
function(fascia_add_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE fascia_catch_main fascia_core fascia_flags ${T_LIBS})
  target_compile_definitions(${T_NAME} PRIVATE
    FASCIA_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    FASCIA_BINARY_DIR="${PROJECT_BINARY_DIR}")
  set_target_properties(${T_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bin/tests)
  catch_discover_tests(${T_NAME} WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
                       PROPERTIES TIMEOUT 300)
endfunction()
