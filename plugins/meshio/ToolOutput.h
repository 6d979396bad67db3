#pragma once
/// The rigid tools in a VTKExporter's series (tools="true"): each tool touching the exporter's body,
/// written at every step the exporter writes as a .vtp surface at its pose, a further part of that
/// timestep in the exporter's .pvd, so that ParaView shows the instrument where it was.
#include "fascia/sim/Tool.h"

#include <string>
#include <vector>

namespace fascia::meshio {

class ToolOutput {
public:
    /// Takes the scene's tools (BaseTool, anywhere under the root) whose body is `body` and that have
    /// a shape to draw (BaseTool::displayMesh), in scene order; their files are named
    /// <base>_<tool's name>_<step>.vtp, in the folder of <outputDir>/<base>. A plane is drawn as a
    /// square of half-side 1.5 times the half-diagonal of the body's rest bounding box. A tool name
    /// that two of them share, that holds a '/', or whose file stem <base>_<name> is in `taken` (the
    /// owner's other series) is an input error of `owner` at `param`. The tools must be initialised.
    void start(const core::Component& owner, const core::BaseParam& param, const core::BaseMechanicalState& body,
               const std::string& base, const std::string& compression, const std::vector<std::string>& taken);
    /// Writes each tool's file of `step` at its current pose (world frame), with the field data
    /// "force" (N) and "torque" (N m, about the pose's position) of BaseTool; returns their names.
    std::vector<std::string> write(long step);
    size_t size() const { return m_tools.size(); }

private:
    struct Tool {
        const core::BaseTool* tool;
        std::string stem;     ///< <base>_<name>
        Positions local;      ///< its display mesh, in its own frame
        Triangles triangles;
    };
    /// The located error when `stem`, the files of tool t, is taken by another tool or series.
    void checkName(const core::BaseParam& param, const core::BaseTool& t, const std::string& stem,
                   const std::vector<std::string>& taken) const;
    const core::Component* m_owner = nullptr;
    std::string m_dir, m_compression;
    std::vector<Tool> m_tools;
    Positions m_world;  ///< one tool's points at its pose (reused)
};

} // namespace fascia::meshio
