# Install rules and the exported CMake package, so an out-of-tree plugin needs only
#   find_package(Fascia REQUIRED)
#   fascia_add_plugin(NAME myplugin SOURCES MyForceField.cpp)
include(CMakePackageConfigHelpers)
set(FASCIA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Fascia)

install(TARGETS fascia_core fascia_flags EXPORT FasciaTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Headers only, from the declared public include folders: a folder that still holds sources gives
# no .cpp, CMakeLists.txt or tests/ to <prefix>/include (tests/install/CheckInstallTree.cmake checks).
set(_fascia_header_filter FILES_MATCHING PATTERN "*.h" PATTERN "tests" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        ${_fascia_header_filter})

# plugins: all into the plugin folder; those with public headers (materials ...) are exported too
get_property(_fascia_plugins GLOBAL PROPERTY FASCIA_INTREE_PLUGINS)
get_property(_fascia_exported GLOBAL PROPERTY FASCIA_EXPORTED_PLUGINS)
foreach(p ${_fascia_plugins})
  if(p IN_LIST _fascia_exported)
    install(TARGETS ${p} EXPORT FasciaTargets LIBRARY DESTINATION ${FASCIA_PLUGIN_SUBDIR})
  else()
    install(TARGETS ${p} LIBRARY DESTINATION ${FASCIA_PLUGIN_SUBDIR})
  endif()
endforeach()
get_property(_fascia_public_includes GLOBAL PROPERTY FASCIA_PUBLIC_INCLUDE_DIRS)
foreach(d ${_fascia_public_includes})
  install(DIRECTORY ${d}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} ${_fascia_header_filter})
endforeach()

# scenes (with their meshes), the examples' sources, the docs and the README: share/fascia
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes ${PROJECT_SOURCE_DIR}/docs DESTINATION ${FASCIA_DATA_SUBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples DESTINATION ${FASCIA_DATA_SUBDIR} PATTERN "__pycache__" EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${FASCIA_DATA_SUBDIR})

# pkg-config, relocatable: the prefix is found from the .pc file's own folder (install folders
# given as absolute paths do not move with the prefix: the file names them as they are)
set(_fascia_pc_dir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(FASCIA_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _fascia_up /root/${_fascia_pc_dir} /root)
  string(REGEX REPLACE "/$" "" _fascia_up "${_fascia_up}")
  set(FASCIA_PC_PREFIX "\${pcfiledir}/${_fascia_up}")
endif()
foreach(_d LIBDIR INCLUDEDIR DATADIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_d}}")
    set(FASCIA_PC_${_d} "${CMAKE_INSTALL_${_d}}")
  else()
    set(FASCIA_PC_${_d} "\${prefix}/${CMAKE_INSTALL_${_d}}")
  endif()
endforeach()
configure_file(${PROJECT_SOURCE_DIR}/cmake/fascia.pc.in ${PROJECT_BINARY_DIR}/fascia.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/fascia.pc DESTINATION ${_fascia_pc_dir})

install(EXPORT FasciaTargets NAMESPACE Fascia:: DESTINATION ${FASCIA_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/FasciaConfig.cmake.in
  ${PROJECT_BINARY_DIR}/FasciaConfig.cmake INSTALL_DESTINATION ${FASCIA_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/FasciaConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/FasciaConfig.cmake ${PROJECT_BINARY_DIR}/FasciaConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FasciaPluginHelpers.cmake
        DESTINATION ${FASCIA_CMAKE_DIR})
