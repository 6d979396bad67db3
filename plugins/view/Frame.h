#pragma once
/// What a picture of a running scene shows, copied out of the simulation between two steps: the
/// bodies' boundary surfaces with a field per surface node, their constrained nodes, the rigid
/// tools' surfaces at their poses, the grab spring. No VTK here: the renderer (SceneRenderer.h)
/// draws a Frame, and the simulation thread fills one (FrameSource) while the render thread draws
/// the previous one (docs/viewer.md).
#include "fascia/sim/Simulation.h"
#include "fascia/sim/Tool.h"

#include <string>
#include <vector>

namespace fascia::view {

/// The fields a surface can be coloured by.
enum class Field { Displacement, VonMises, J, None };
/// "displacement", "vonMises", "J", "none"; anything else is an input error listing them.
Field parseField(const std::string& name);
const char* fieldName(Field f);
const char* fieldUnit(Field f);

struct BodyFrame {
    std::string name;             ///< the mechanical state's path
    Positions points;             ///< the surface nodes' positions (m)
    Triangles triangles;          ///< over `points`, outwards (the same in every frame)
    IndexList stateNodes;         ///< the state's node of each surface point
    std::vector<double> field;    ///< one value per surface point (empty for Field::None)
    IndexList constrained;        ///< surface points held by a constraint (indices into points)
};

struct ToolFrame {
    std::string name;
    Positions points;             ///< the tool's display mesh in the world frame, at its pose
    Triangles triangles;
    Vec3 force = Vec3::Zero();    ///< the force of the body on the tool (N)
    core::Pose pose;
};

/// The spring of a mouse grab: from the grabbed node to the cursor's point.
struct GrabFrame {
    bool active = false;
    Vec3 node = Vec3::Zero(), target = Vec3::Zero(), force = Vec3::Zero();
};

struct Frame {
    double time = 0;
    long step = 0;
    Field field = Field::Displacement;
    std::vector<BodyFrame> bodies;
    std::vector<ToolFrame> tools;
    GrabFrame grab;
};

/// Copies frames out of a simulation. Built once per simulation (the surfaces, the tools' display
/// meshes and the constrained nodes are worked out here); capture() copies the moving parts.
class FrameSource {
public:
    /// Every mechanical state of the scene below `root` (an initialised one) with a boundary
    /// surface is a body; `surfaceName`, when not empty, is the only one (a state or a visual
    /// surface, by name or path). An input error when the scene has no surface to show. Built from
    /// the scene graph, not the Simulation, so that an observer (PngSnapshot) can make one.
    FrameSource(const core::Node& root, Field field, const std::string& surfaceName = "");
    /// The current state into `out` (the triangles are copied only when out has none yet), at
    /// time t and step `step`. The state must be on the host (Simulation::fetchState).
    void capture(Frame& out, double t, long step) const;
    /// The mechanical state of body b; the state's node of its surface point i; the summed mass of
    /// a state node (kg); whether its surface points are the state's nodes (not a visual surface).
    core::BaseMechanicalState& state(size_t b) const { return *m_bodies[b].state; }
    int stateNode(size_t b, int i) const { return m_bodies[b].nodes[i]; }
    double nodeMass(size_t b, int node) const;
    bool grabbable(size_t b) const { return !m_bodies[b].visual; }
    size_t bodyCount() const { return m_bodies.size(); }
    /// The tools, in scene order.
    const std::vector<core::BaseTool*>& tools() const { return m_tools; }
    Field field() const { return m_field; }
    /// The half-diagonal of the bodies' rest bounding box (m), for a plane tool's square.
    double extent() const { return m_extent; }

private:
    struct Body {
        std::string name;                   ///< the component's path
        core::BaseMechanicalState* state = nullptr;
        const Positions* points = nullptr;  ///< what moves: the state's x or a visual surface's points
        Positions rest;                     ///< the surface points at capture time zero
        Triangles triangles;                ///< compacted to the surface points
        IndexList nodes;                    ///< surface point -> index into *points
        IndexList constrained;
        std::vector<core::BaseForceField*> elementFields;  ///< those with elements, for VonMises and J
        std::vector<const core::BaseMass*> masses;          ///< the masses acting on the state
        bool visual = false;                ///< a visual surface (displacement only)
    };
    /// A state with a boundary surface, or a visual surface, as a body; false for anything else.
    bool addBody(const core::Component& c, const core::Node& root);
    void nodeField(const Body& b, std::vector<double>& out) const;
    Field m_field;
    std::vector<Body> m_bodies;
    std::vector<core::BaseTool*> m_tools;
    std::vector<Positions> m_toolPoints;
    std::vector<Triangles> m_toolTriangles;
    double m_extent = 0;
};

} // namespace fascia::view
