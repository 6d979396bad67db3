#pragma once
/// A ParaView time series of a triangle surface: <base>_<step>.vtp files and their own <base>.pvd,
/// and the writing of one such .vtp file (writeSurfaceFile, which the VTKExporter's tools use too).
/// Written with VTK's XML writer (this file's .cpp includes VTK; a build without VTK has none).
#include "PvdSeries.h"
#include "fascia/base/Component.h"

#include <filesystem>
#include <string>
#include <vector>

namespace fascia::meshio {

/// One frame of a surface: its points, triangles indexing them, and point arrays of 3 components.
struct SurfaceFrame {
    const Positions* points = nullptr;
    const Triangles* triangles = nullptr;
    struct Array {
        const char* name;
        const Positions* values;  ///< one per point
    };
    std::vector<Array> arrays;
    const IndexList* nodeIds = nullptr;  ///< optional integer point array "nodeId" (the body's node of each point)
    /// Field data: arrays of one 3-component tuple for the whole surface (a tool's force).
    struct Field {
        const char* name;
        Vec3 value;
    };
    std::vector<Field> fields;
};

/// Writes one frame as the .vtp file `target` (through a temporary file and a rename); compression
/// "lz4", "zlib" or "none". A located output error of `owner` when it cannot.
void writeSurfaceFile(const core::Component& owner, const SurfaceFrame& frame, const std::filesystem::path& target,
                      const std::string& compression);

class SurfaceSeries {
public:
    /// Starts the series <outputDir>/<base>.pvd for `owner` (which claims the file, so that two
    /// components cannot write one series), removing the temporaries a killed run left.
    /// compression: "lz4", "zlib" or "none".
    void start(const core::Component& owner, const std::string& base, const std::string& compression);
    /// Writes <base>_<step>.vtp (through a temporary file and a rename) and lists it in the .pvd.
    void write(double t, long step, const SurfaceFrame& frame);
    /// Completes the .pvd (end of the run).
    void finish() { m_pvd.finish(); }
    bool started() const { return !m_base.empty(); }
    long lastStep() const { return m_lastStep; }
    /// The checkpoint of the series (PvdSeries::saveState, and the last step written), as records
    /// named <prefix>...; restoreState reads them back after start().
    void saveState(core::StateWriter& out, const std::string& prefix) const;
    void restoreState(core::StateReader& in, const std::string& prefix);

private:
    const core::Component* m_owner = nullptr;
    std::string m_dir, m_base, m_compression;
    PvdSeries m_pvd;
    long m_lastStep = -1;
};

} // namespace fascia::meshio
