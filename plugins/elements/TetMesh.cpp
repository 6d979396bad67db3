#include "fascia/elements/TetMesh.h"

#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

#include <string>

namespace fascia::elements {

core::ParamSpec tetMeshParam() {
    return core::ParamSpec("mesh").help(
        "mesh with the tetrahedra (and groups, cell arrays), e.g. \"@loader.mesh\"; default: the mesh source in the context");
}

core::ParamSpec tetrahedraParam() {
    return core::ParamSpec("tetrahedra").help(
        "tetrahedra (4 node indices each), inline or e.g. \"@loader.tetrahedra\" (instead of mesh)");
}

namespace {
const MeshData* meshSource(const core::Component& owner, const core::Param<MeshData>& mesh, const core::Param<Tetrahedra>& tets) {
    if (mesh.isSet()) return &mesh.get();
    if (tets.isSet() || !owner.node()) return nullptr;
    if (auto* topo = owner.node()->findInContext<core::BaseTopology>()) return &topo->meshData();
    return nullptr;
}
} // namespace

TetMesh resolveTetMesh(const core::Component& owner, const core::Param<MeshData>& meshParam, const core::Param<Tetrahedra>& tetParam) {
    if (meshParam.isSet() && tetParam.isSet())
        owner.fail(tetParam, "give the tetrahedra either by 'mesh' or by 'tetrahedra', not both");
    TetMesh out;
    out.mesh = meshSource(owner, meshParam, tetParam);
    if (tetParam.isSet()) out.tets = tetParam.get();
    else if (out.mesh) out.tets = out.mesh->tetrahedra;
    else owner.fail("no tetrahedra: set mesh=\"@loader.mesh\" or tetrahedra=\"@loader.tetrahedra\", or put a MeshLoader or GridMesh in the node");
    if (out.tets.empty())
        owner.fail(tetParam.isSet() ? static_cast<const core::BaseParam&>(tetParam) : meshParam, "the mesh has no tetrahedra");

    // rest positions: the state's, else the mesh's points
    core::BaseMechanicalState* state = owner.node() ? owner.node()->findInContext<core::BaseMechanicalState>() : nullptr;
    if (state && state->size() > 0) out.rest = state->x0();
    else if (out.mesh && !out.mesh->points.empty()) out.rest = out.mesh->points;
    else owner.fail("no rest positions: put a MechanicalObject in the node (or give a mesh with points)");
    const size_t n = out.rest.size();
    for (size_t e = 0; e < out.tets.size(); ++e)
        for (int a = 0; a < 4; ++a)
            if (out.tets[e][a] < 0 || size_t(out.tets[e][a]) >= n)
                owner.fail("tetrahedron " + std::to_string(e) + " has node " + std::to_string(out.tets[e][a]) + " but there are " +
                           std::to_string(n) + " nodes");
    return out;
}

void addTetMeshDependencies(const core::Component& owner, const core::Param<MeshData>& mesh,
                            const core::Param<Tetrahedra>& tetrahedra, std::vector<core::Component*>& deps) {
    if (!owner.node() || mesh.isSet() || tetrahedra.isSet()) return;
    if (auto* topo = owner.node()->findInContext<core::BaseTopology>()) deps.push_back(topo);
}

} // namespace fascia::elements
