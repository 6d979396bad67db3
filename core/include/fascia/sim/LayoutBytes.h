#pragma once
/// What one force evaluation moves through memory, counted from a force field's arrays as they are
/// after init (fascia-bench reports it per element and step beside the measured time;
/// docs/performance.md, "Method", bytes from the layout).
#include <cstddef>

namespace fascia::core {

/// Every array a pass of the evaluation reads counts once with its full size, and once more for
/// each pass that writes it (read-modify-write: twice); caches are ignored, so the figure is the
/// traffic of a mesh far larger than the caches (docs/performance.md, Method).
struct LayoutBytes {
    size_t elementData = 0;  ///< per-element arrays: precomputed data, connectivity, viscous states
    size_t nodeRows = 0;     ///< per-node arrays: positions, displacements, forces, renumbering
    size_t buffers = 0;      ///< per-block node buffers (rows) and their index lists
    size_t total() const { return elementData + nodeRows + buffers; }
};

/// Implemented beside BaseForceField by the force fields that count their bytes (HEML, TLED):
/// fascia-bench finds it with dynamic_cast, so that BaseForceField (and every file that includes
/// it) stays as it is.
class LayoutReport {
public:
    virtual ~LayoutReport();
    /// What one addForce() moves (LayoutBytes).
    virtual LayoutBytes layoutBytes() const = 0;
};

} // namespace fascia::core
