#pragma once
/// Reading input files (scenes, includes, meshes) that other people made: only regular files of a
/// bounded size, checked before anything blocks or allocates. A FIFO would block open() forever and
/// /dev/zero would never end, so both are refused from their file type, without reading them.
#include "fascia/base/Error.h"

#include <cstdint>
#include <string>

namespace fascia::core {

/// Largest scene or include file read (64 MiB).
constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t(64) << 20;
/// Largest mesh file read (8 GiB: an ASCII mesh of a few million tetrahedra is a few hundred MB).
constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(8) << 30;

/// Fails (a located input error at loc) unless path names an existing regular file of at most
/// maxBytes bytes. A folder, FIFO, socket or device is refused from its type (stat), without being
/// opened. `what` names the file in messages ("scene file", "mesh file"). Returns the size in bytes.
std::uintmax_t requireRegularFile(const std::string& path, const std::string& what, std::uintmax_t maxBytes,
                                  const SourceLoc& loc);

/// Reads a whole file checked as requireRegularFile does; the file is opened non-blocking and its
/// type checked again on the open descriptor, and reading stops past maxBytes (a file that grows
/// while it is read is refused too).
std::string readRegularFile(const std::string& path, const std::string& what, std::uintmax_t maxBytes,
                            const SourceLoc& loc);

} // namespace fascia::core
