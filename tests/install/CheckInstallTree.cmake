# cmake -DBUILD_DIR=<build> -DWORK_DIR=<empty folder> -P CheckInstallTree.cmake
#
# Installs the build into WORK_DIR/prefix and checks that the installed tree holds headers,
# libraries, the programs, the CMake package, the pkg-config file and share/fascia only:
#   - no source file (.cpp) and no CMakeLists.txt but the examples' (share/fascia/examples) and the
#     package's (lib/cmake); no tests/ folder;
#   - include/ holds headers (.h) only, lib/cmake/ CMake files (.cmake) only, lib/pkgconfig/
#     fascia.pc only, lib/python3.X/dist-packages/fascia the Python package (its .py files and the
#     extension), lib/ otherwise libraries (.so, .so.N..., .a) only, bin/ the programs only
#     (fascia-run, fascia-bench);
#   - share/fascia/ holds the scenes with their meshes, the docs, the examples and the README, and
#     each of those is there;
#   - nothing at the top of the prefix but bin/, include/, lib/ and share/.
# Every offending path is printed, then the check fails.
cmake_policy(SET CMP0057 NEW)  # if(... IN_LIST ...)
foreach(v BUILD_DIR WORK_DIR)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "CheckInstallTree.cmake: -D${v}=... is required")
  endif()
endforeach()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${prefix})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}):\n${out}\n${err}")
endif()

file(GLOB_RECURSE files LIST_DIRECTORIES false RELATIVE ${prefix} ${prefix}/*)
file(GLOB_RECURSE dirs LIST_DIRECTORIES true RELATIVE ${prefix} ${prefix}/*)
list(REMOVE_ITEM dirs ${files})
if(NOT files)
  message(FATAL_ERROR "the install into ${prefix} holds no files")
endif()

set(bad)
foreach(d ${dirs})
  if(d MATCHES "(^|/)tests$")
    list(APPEND bad "${d}/: a tests folder")
  endif()
endforeach()
foreach(f ${files})
  if(f MATCHES "^share/fascia/")
    if(NOT f MATCHES "^share/fascia/(scenes|docs|examples)/" AND NOT f STREQUAL "share/fascia/README.md")
      list(APPEND bad "${f}: share/fascia holds scenes/, docs/, examples/ and README.md only")
    endif()
  elseif(f MATCHES "\\.(cpp|cc|cxx|c)$")
    list(APPEND bad "${f}: a source file")
  elseif(f MATCHES "(^|/)CMakeLists\\.txt$" AND NOT f MATCHES "^lib/cmake/")
    list(APPEND bad "${f}: a CMakeLists.txt outside lib/cmake")
  elseif(f MATCHES "^include/")
    if(NOT f MATCHES "\\.h$")
      list(APPEND bad "${f}: not a header (include/ holds .h files only)")
    endif()
  elseif(f MATCHES "^lib/pkgconfig/")
    if(NOT f STREQUAL "lib/pkgconfig/fascia.pc")
      list(APPEND bad "${f}: lib/pkgconfig/ holds fascia.pc only")
    endif()
  elseif(f MATCHES "^lib/cmake/")
    if(NOT f MATCHES "\\.cmake$")
      list(APPEND bad "${f}: not a CMake file (lib/cmake/ holds the package only)")
    endif()
  elseif(f MATCHES "^lib/python3[.0-9]*/dist-packages/fascia/")
    if(NOT f MATCHES "/fascia/[_a-z]+\\.py$" AND NOT f MATCHES "/fascia/_fascia[^/]*\\.so$")
      list(APPEND bad "${f}: not a file of the Python package fascia")
    endif()
  elseif(f MATCHES "^lib/")
    if(NOT f MATCHES "\\.(so(\\.[0-9]+)*|a)$")
      list(APPEND bad "${f}: not a library")
    endif()
  elseif(f MATCHES "^bin/")
    if(NOT f MATCHES "^bin/fascia-(run|bench|view|plot)$")
      list(APPEND bad "${f}: not one of the programs")
    endif()
  else()
    list(APPEND bad "${f}: outside bin/, include/, lib/ and share/fascia/")
  endif()
endforeach()
foreach(f share/fascia/README.md share/fascia/scenes/heml/abdomen.xml share/fascia/scenes/meshes/README.md
          share/fascia/scenes/meshes/organ_2428.msh share/fascia/docs/design.md
          share/fascia/examples/plugin/CMakeLists.txt share/fascia/examples/haptics/CMakeLists.txt
          lib/pkgconfig/fascia.pc)
  if(NOT f IN_LIST files)
    list(APPEND bad "${f}: missing")
  endif()
endforeach()

# the installed Python package imports from its install folder alone and finds the installed plugins
file(GLOB _py_dirs LIST_DIRECTORIES true ${prefix}/lib/python3*/dist-packages)
if(_py_dirs AND EXISTS /usr/bin/python3)
  list(GET _py_dirs 0 _py_dir)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${_py_dir} /usr/bin/python3 -c
                          "import fascia, sys; assert fascia.__file__.startswith(sys.argv[1]), fascia.__file__; assert 'HEMLForceField' in fascia.components(); print(fascia.__file__)"
                          ${_py_dir}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    list(APPEND bad "the installed Python package does not import from ${_py_dir}: ${out}${err}")
  endif()
endif()

list(LENGTH files n)
if(bad)
  list(LENGTH bad nbad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "the installed tree (${n} files) holds ${nbad} thing(s) it must not:\n  ${text}")
endif()
message(STATUS "installed tree: ${n} files, headers, libraries, programs, the packages and share/fascia only")
file(REMOVE_RECURSE ${prefix})
