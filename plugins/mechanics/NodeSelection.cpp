#include "NodeSelection.h"
#include "fascia/scene/Node.h"

#include <algorithm>

namespace fascia::mechanics {

core::ParamSpec NodeSelection::spec(const char* name) {
    if (std::string(name) == "indices")
        return core::ParamSpec("indices").help("node indices (0-based), inline or linked (e.g. \"@box.indices\")");
    return core::ParamSpec("group").help("name of a node group of the mesh source in the context (a Gmsh physical group, a GridMesh face such as \"xmin\")");
}

IndexList NodeSelection::resolve(const core::Component& owner, const core::BaseMechanicalState& state) const {
    if (indices.isSet() && group.isSet()) owner.fail(group, "give indices or group, not both");
    IndexList out;
    if (group.isSet()) {
        auto* topo = owner.node()->findInContext<core::BaseTopology>();
        if (!topo) owner.fail(group, "group = \"" + group.get() + "\" but no mesh source (MeshLoader, GridMesh) is in the context");
        const auto& groups = topo->meshData().nodeGroups;
        auto it = groups.find(group.get());
        if (it == groups.end()) {
            std::vector<std::string> names;
            for (auto& [n, g] : groups) names.push_back(n);
            std::string all;
            for (auto& n : names) all += (all.empty() ? "" : ", ") + n;
            std::vector<std::string> notes;
            for (auto& s : core::closestMatches(group.get(), names)) notes.push_back("did you mean '" + s + "'?");
            notes.push_back("groups of '" + topo->name() + "': " + (all.empty() ? "(none)" : all));
            owner.fail(group, "no node group '" + group.get() + "'", notes);
        }
        out = it->second;
    } else if (indices.isSet()) {
        out = indices.get();
    } else {
        owner.fail("give the nodes: indices=\"...\" or group=\"...\"");
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    if (!out.empty() && size_t(out.back()) >= state.size())
        owner.fail(group.isSet() ? static_cast<const core::BaseParam&>(group) : indices,
                   "node index " + std::to_string(out.back()) + " is out of range: the state '" + state.name() + "' has " +
                       std::to_string(state.size()) + " nodes");
    return out;
}

core::ParamSpec axisMaskSpec(const char* name, const char* help) {
    return core::ParamSpec(name).count(3).min(0).max(1).help(help);
}

std::array<bool, 3> readAxisMask(const core::Component& owner, const core::Param<IndexList>& mask) {
    const auto& m = mask.get();
    if (m.size() != 3) owner.fail(mask, mask.name() + " needs three 0/1 flags \"x y z\"");
    if (m[0] + m[1] + m[2] == 0) owner.fail(mask, mask.name() + " = \"0 0 0\" selects no axis");
    return {m[0] == 1, m[1] == 1, m[2] == 1};
}

const MeshData& contextMesh(const core::Component& c, const core::BaseMechanicalState& state) {
    auto* topo = c.node()->findInContext<core::BaseTopology>();
    if (!topo) c.fail("needs a mesh source (MeshLoader, GridMesh) in its context");
    const MeshData& mesh = topo->meshData();
    if (mesh.points.size() != state.size())
        c.fail("the mesh source '" + topo->name() + "' has " + std::to_string(mesh.points.size()) +
               " points but the state '" + state.name() + "' has " + std::to_string(state.size()) + " nodes");
    return mesh;
}

core::BaseMechanicalState& contextState(const core::Component& c) {
    auto* s = c.node()->findInContext<core::BaseMechanicalState>();
    if (!s) c.fail("no MechanicalObject in its context: put one in the same node or a parent");
    return *s;
}

} // namespace fascia::mechanics
