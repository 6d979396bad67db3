#pragma once
/// The "which nodes" parameters shared by constraints and loads: indices or a named node group.
#include "fascia/sim/Mechanics.h"

namespace fascia::mechanics {

class NodeSelection {
public:
    explicit NodeSelection(core::Component* owner) : indices(owner, spec("indices")), group(owner, spec("group")) {}
    /// Resolves to sorted unique node indices, checked against the state size (located errors).
    IndexList resolve(const core::Component& owner, const core::BaseMechanicalState& state) const;

    core::Param<IndexList> indices;
    core::Param<std::string> group;

private:
    static core::ParamSpec spec(const char* name);
};

/// Per-axis mask "1 1 0" (1: constrained/applied along that axis).
core::ParamSpec axisMaskSpec(const char* name, const char* help);
/// Checks a mask has three 0/1 entries; returns it as booleans.
std::array<bool, 3> readAxisMask(const core::Component& owner, const core::Param<IndexList>& mask);

/// The state in the component's context, or a located error.
core::BaseMechanicalState& contextState(const core::Component& c);
/// The mesh of the mesh source in the component's context, checked to have one point per node of
/// the state (located errors otherwise).
const MeshData& contextMesh(const core::Component& c, const core::BaseMechanicalState& state);

} // namespace fascia::mechanics
