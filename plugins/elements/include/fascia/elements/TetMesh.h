#pragma once
/// The tetrahedra of a tetrahedral force field, resolved once at init from its 'mesh' and
/// 'tetrahedra' parameters or the mesh source in its context, with the rest positions: written once
/// for HEML and elements::TetForceField (docs/design.md, principle 9).
#include "fascia/base/Component.h"
#include "fascia/base/Param.h"
#include "fascia/base/Types.h"

#include <vector>

namespace fascia::elements {

/// The declaration of the 'mesh' parameter of a tetrahedral force field (one text for all of them).
core::ParamSpec tetMeshParam();
/// The declaration of its 'tetrahedra' parameter.
core::ParamSpec tetrahedraParam();

/// What resolveTetMesh finds.
struct TetMesh {
    Tetrahedra tets;                 ///< input order
    const MeshData* mesh = nullptr;  ///< the mesh they came from (groups, cell arrays), or null
    Positions rest;                  ///< rest positions: the state's in the context, else the mesh's points
};

/// The tetrahedra from 'tetrahedra', else from 'mesh', else from the mesh source (BaseTopology) in
/// owner's context, and the rest positions. Fails located at owner (or the parameter) when both
/// parameters are given, when there are no tetrahedra or no rest positions, and when a tetrahedron
/// names a node out of range.
TetMesh resolveTetMesh(const core::Component& owner, const core::Param<MeshData>& mesh, const core::Param<Tetrahedra>& tetrahedra);

/// Adds the mesh source in owner's context to deps when neither parameter is given (init order).
void addTetMeshDependencies(const core::Component& owner, const core::Param<MeshData>& mesh,
                            const core::Param<Tetrahedra>& tetrahedra, std::vector<core::Component*>& deps);

} // namespace fascia::elements
