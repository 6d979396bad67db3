#!/usr/bin/env bash
# Makes the dependency bundle that tools/gpu-check.sh brings to a GPU machine that has the CUDA
# toolkit, CMake, ninja and a C++ compiler but none of Fascia's other dependencies and no network:
# Eigen's headers (MPL-2.0), TinyXML2's header and shared library (zlib licence) and Catch2 v2's
# single header with its CMake test discovery (BSL-1.0), copied from this machine's Debian packages
# (libeigen3-dev, libtinyxml2-dev, libtinyxml2-9, catch2) with their copyright files, plus small
# CMake package files written here. All three licences allow redistribution with the notices kept.
# The bundle is not committed (tools/gpu-deps/ is ignored); it is made here and carried at run time.
#   tools/make-gpu-deps.sh [OUT_DIR]    (default tools/gpu-deps; also writes OUT_DIR.tar.gz)
# Caveat: libtinyxml2.so is a Debian 12 (glibc 2.36, x86-64) binary; the GPU machine's C library
# must be as new (TinyXML2's sources are not in the Debian packages).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-$here/gpu-deps}
rm -rf "$out"
mkdir -p "$out/include" "$out/lib/cmake/tinyxml2" "$out/lib/cmake/Catch2" "$out/share/eigen3/cmake" "$out/licences"

# Eigen: headers only
cp -r /usr/include/eigen3 "$out/include/eigen3"
cp /usr/share/eigen3/cmake/Eigen3ConfigVersion.cmake "$out/share/eigen3/cmake/"
cat > "$out/share/eigen3/cmake/Eigen3Config.cmake" <<'CM'
# Eigen3::Eigen from the bundled headers (tools/make-gpu-deps.sh)
if(NOT TARGET Eigen3::Eigen)
  add_library(Eigen3::Eigen INTERFACE IMPORTED)
  set_target_properties(Eigen3::Eigen PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${CMAKE_CURRENT_LIST_DIR}/../../../include/eigen3")
endif()
set(EIGEN3_INCLUDE_DIR "${CMAKE_CURRENT_LIST_DIR}/../../../include/eigen3")
CM
cp /usr/share/doc/libeigen3-dev/copyright "$out/licences/eigen3-copyright"

# TinyXML2: header and shared library
cp /usr/include/tinyxml2.h "$out/include/"
so=$(readlink -f /usr/lib/x86_64-linux-gnu/libtinyxml2.so)
cp "$so" "$out/lib/"
soname=$(basename "$(readlink /usr/lib/x86_64-linux-gnu/libtinyxml2.so)")
ln -s "$(basename "$so")" "$out/lib/$soname"
ln -s "$soname" "$out/lib/libtinyxml2.so"
ver=$(grep -E '^set\(PACKAGE_VERSION ' /usr/lib/x86_64-linux-gnu/cmake/tinyxml2/tinyxml2-config-version.cmake | sed -E 's/.*"(.*)".*/\1/')
cat > "$out/lib/cmake/tinyxml2/tinyxml2-config.cmake" <<CM
# tinyxml2::tinyxml2 from the bundled header and library (tools/make-gpu-deps.sh)
if(NOT TARGET tinyxml2::tinyxml2)
  add_library(tinyxml2::tinyxml2 SHARED IMPORTED)
  set_target_properties(tinyxml2::tinyxml2 PROPERTIES
    IMPORTED_LOCATION "\${CMAKE_CURRENT_LIST_DIR}/../../$soname"
    IMPORTED_SONAME "$soname"
    INTERFACE_INCLUDE_DIRECTORIES "\${CMAKE_CURRENT_LIST_DIR}/../../../include")
endif()
CM
cat > "$out/lib/cmake/tinyxml2/tinyxml2-config-version.cmake" <<CM
set(PACKAGE_VERSION "$ver")
set(PACKAGE_VERSION_COMPATIBLE TRUE)
if(PACKAGE_FIND_VERSION STREQUAL PACKAGE_VERSION)
  set(PACKAGE_VERSION_EXACT TRUE)
endif()
CM
cp /usr/share/doc/libtinyxml2-dev/copyright "$out/licences/tinyxml2-copyright"

# Catch2 v2: the single header and CMake's test discovery
mkdir -p "$out/include/catch2"
cp /usr/include/catch2/catch.hpp "$out/include/catch2/"
cp /usr/lib/cmake/Catch2/Catch.cmake /usr/lib/cmake/Catch2/CatchAddTests.cmake /usr/lib/cmake/Catch2/Catch2ConfigVersion.cmake "$out/lib/cmake/Catch2/"
cat > "$out/lib/cmake/Catch2/Catch2Config.cmake" <<'CM'
# Catch2::Catch2 from the bundled single header (tools/make-gpu-deps.sh); include(Catch) finds Catch.cmake here
if(NOT TARGET Catch2::Catch2)
  add_library(Catch2::Catch2 INTERFACE IMPORTED)
  set_target_properties(Catch2::Catch2 PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${CMAKE_CURRENT_LIST_DIR}/../../../include")
endif()
list(APPEND CMAKE_MODULE_PATH "${CMAKE_CURRENT_LIST_DIR}")
CM
cp /usr/share/doc/catch2/copyright "$out/licences/catch2-copyright"

tar -C "$(dirname "$out")" -czf "$out.tar.gz" "$(basename "$out")"
echo "bundle: $out ($(du -sh "$out" | cut -f1)), $out.tar.gz ($(du -h "$out.tar.gz" | cut -f1))"
