#pragma once
/// The .pvd index of a ParaView time series, shared by every series the exporters write (the
/// VTKExporter's .vtu volume with its tools' .vtp, its .vtp surface, a visual surface's .vtp).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace fascia::core {
class Component;
class StateWriter;
class StateReader;
} // namespace fascia::core

namespace fascia::meshio {

/// One timestep of a series: its time and its files, part 0, 1 ... (the body's .vtu, then its
/// tools' .vtp: ParaView shows the parts of a timestep together). The files are names beside the
/// .pvd (no folder).
struct PvdStep {
    double t = 0;
    std::vector<std::string> parts;
};

/// Lists the timesteps of a series in a .pvd file, a DataSet per part. It is rewritten after every
/// file while the series is short; past 100 files at most once a second of wall time (a full
/// rewrite per file would grow quadratically; docs/performance.md, lesson 15), and always by
/// finish(). The time is core::timerNow(): std::chrono::steady_clock unless a test injects a clock.
class PvdSeries {
public:
    /// Starts an empty series indexed by `pvdPath`.
    void reset(std::string pvdPath);
    /// Adds the files written for time t, listed as its parts 0, 1 ... in this order (one file: the
    /// timestep's only part); names beside the .pvd.
    void add(double t, std::vector<std::string> parts);
    /// Rewrites the index when it lacks files (end of the run).
    void finish();
    size_t size() const { return m_written.size(); }
    /// The timesteps so far, for a checkpoint; restore() puts them back after a restart, the index on
    /// disk taken as listing them (it is rewritten with the next file).
    const std::vector<PvdStep>& steps() const { return m_written; }
    void restore(std::vector<PvdStep> steps);
    const std::string& path() const { return m_path; }
    /// The checkpoint of a series: steps() as the records <prefix>times (one per timestep) and
    /// <prefix>files (a line per timestep, its parts separated by '/', which no file name holds: a
    /// checkpoint written before parts existed reads as one part per timestep).
    void saveState(core::StateWriter& out, const std::string& prefix) const;
    /// Reads them back into restore(); errors name `owner`. A warning of `owner` when a file of the
    /// series is not beside the .pvd (the .pvd lists it all the same: restart into the output folder
    /// of the run that wrote the checkpoint).
    void restoreState(core::StateReader& in, const std::string& prefix, const core::Component& owner);

private:
    void write();
    std::string m_path;
    std::vector<PvdStep> m_written;
    size_t m_files = 0;           ///< files in m_written, over all parts
    size_t m_listed = 0;          ///< timesteps listed in the .pvd on disk
    double m_lastWrite = 0;       ///< core::timerNow() (s) at its last rewrite
};

/// The file of one step of a series whose files are named by `base` (a filename= value, relative to
/// the output folder `dir`): "<base's file name>_<step in 6 digits><extension>" in dir/<base's folder>,
/// which is created.
struct SeriesFile {
    std::string name;            ///< the file's name, as the .pvd lists it
    std::filesystem::path path;  ///< where it is written
};
SeriesFile seriesFile(const std::string& dir, const std::string& base, long step, const char* extension);

/// Writes text to path through a temporary file and a rename (atomic on POSIX file systems).
void writeFileAtomically(const std::string& path, const std::string& text);

/// Removes the temporary files (".<stem>_*.tmp", ".<pvd>.tmp") that a killed run left beside
/// the .pvd of a series whose files are named <stem>_<step>.
void removeStaleTemporaries(const std::string& pvdPath, const std::string& stem);

} // namespace fascia::meshio
