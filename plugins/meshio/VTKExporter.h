#pragma once
#include "PvdSeries.h"
#include "SurfaceSeries.h"
#include "ToolOutput.h"
#include "fascia/sim/Mechanics.h"

#include <vector>

namespace fascia::meshio {

/// Writes a ParaView time series: <outputDir>/<filename>.pvd plus one .vtu per output step, with
/// point data displacement, velocity, force and reaction. Its cells are the elements of every element
/// force field acting on the state, in scene order (each one's tetrahedra, then its hexahedra), else
/// those of the mesh source in its context, with the cell data the force fields provide (J,
/// stresses ...): one array per quantity over all cells, NaN in the cells of a force field that does
/// not offer it (a quantity two force fields offer with different shapes gets an array per force
/// field, "name_forceFieldName"). With two or more force fields a cell array "forceField" gives each
/// cell's force field (0, 1 ... in scene order). Each file is written under a temporary name and
/// renamed, so a run killed at any moment leaves only complete files (and the .pvd lists only those). The .pvd is
/// rewritten after every file while the series is short; past 100 files at most once a second of
/// wall time (a full rewrite per file would grow quadratically), and always at the end of the run.
/// The time is core::timerNow(): std::chrono::steady_clock unless a test injects a clock.
/// With surface="true" it also writes the body's boundary surface (BaseTopology::boundaryTriangles
/// of the mesh source in its context) at the same steps, as <filename>_surface.pvd and one .vtp per
/// step holding only the boundary nodes, with point data displacement, velocity and nodeId (the
/// state's node index). Off by default: the .vtu already holds the volume, whose surface ParaView
/// extracts, and a second file per frame costs write time (docs/performance.md, lesson 15); scenes
/// that render the surface elsewhere turn it on.
/// With tools="true" (the default) each rigid tool touching the state (BaseTool whose body() is it,
/// anywhere in the scene) is written at the same steps as <filename>_<tool's name>_<step>.vtp: its
/// surface (BaseTool::displayMesh; a plane as a square of half-side 1.5 times the body's rest
/// half-diagonal) at its pose in the world frame, with field data force (N) and torque (N m, about
/// the pose's position), the tool's at that step. The .pvd lists these as parts 1, 2 ... of the
/// timestep whose part 0 is the body's .vtu, so that ParaView opens one .pvd and shows the body and
/// its instruments together. A tool without a shape to draw is left out.
class VTKExporter : public core::BaseObserver {
public:
    void init() override;
    void observe(double t, long step) override;
    bool records(long step) const override { return step % m_every.get() == 0; }
    /// The final state of the run, when `every` skipped it.
    void observeFinal(double t, long step) override;
    void cleanup() override;
    /// The default ones, and with tools="true" every tool of the scene: a tool knows its body once
    /// initialised.
    std::vector<core::Component*> dependencies() const override;
    /// The files of the series so far (time and names, for the .pvd: the .vtu and its tools' .vtp)
    /// and the step of the last one, for the volume series and (surface="true") the surface series:
    /// a restored run lists the earlier files in each .pvd (a warning when one is not in the output
    /// folder).
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;

    core::Param<std::string> m_filename{this, core::ParamSpec("filename").help("base name of the files, relative to the output folder (default: the component's name)")};
    core::Param<int> m_every{this, core::ParamSpec("every").min(1).help("write every N steps (the initial and the final state are always written)"), 1};
    core::Param<std::string> m_compression{this, core::ParamSpec("compression").choices({"lz4", "zlib", "none"}).help(
        "compression of the data in the .vtu files: lz4 (fast; ParaView 5.5 and later), zlib (smaller, about 10 "
        "times slower to write) or none"), "lz4"};
    core::Param<bool> m_cellData{this, core::ParamSpec("cellData").help("write the force fields' per-element data (J, stresses)"), true};
    core::Param<bool> m_surface{this, core::ParamSpec("surface").help("also write the body's boundary surface as a .vtp series (<filename>_surface.pvd)"), false};
    core::Param<bool> m_tools{this, core::ParamSpec("tools").help(
        "also write each rigid tool touching the state as a .vtp surface at its pose, with its force and torque as field "
        "data (<filename>_<tool>_<step>.vtp), listed in the .pvd as further parts of each timestep"), true};
    core::Link<core::BaseMechanicalState> m_state{this, core::ParamSpec("state").help("the state to write (default: the one in the context)")};

private:
    /// The boundary nodes and triangles of surface="true".
    void initSurface();
    void writeStep(double t, long step);
    void writeSurface(double t, long step);
    core::BaseMechanicalState* m_st = nullptr;
    std::vector<core::BaseForceField*> m_forceFields;
    PvdSeries m_pvd;
    std::string m_base;
    long m_lastStep = -1;         ///< the step of the last file written
    // the boundary surface (surface="true"): its nodes (state indices) and triangles over them
    SurfaceSeries m_surfaceSeries;
    IndexList m_surfaceNodes;
    Triangles m_surfaceTriangles;
    Positions m_surfacePoints, m_surfaceDisplacement, m_surfaceVelocity;
    ToolOutput m_toolOutput;  ///< the tools (tools="true")
};

} // namespace fascia::meshio
