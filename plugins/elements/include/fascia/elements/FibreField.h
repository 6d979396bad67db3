#pragma once
/// The fibre directions of the elements: per element from a mesh cell array (fibreArray,
/// fibreArray2: 3 numbers per cell, tetrahedra first, then hexahedra), else per material
/// (BaseMaterial::fibreDirection). Unit length; only for elements whose material reads them.
#include "fascia/base/Component.h"
#include "fascia/materials/Material.h"

#include <string>
#include <vector>

namespace fascia::elements {

/// Fibre directions a0 (which = 0) or b0 (which = 1) of every cell.
struct FibreField {
    bool used = false;        ///< some material reads this direction
    bool perElement = false;  ///< from a cell array (else each material's own)
    std::vector<Vec3> dir;    ///< per cell (tetrahedra, then hexahedra); zero where the material does not read it
};

/// Resolves one fibre direction for cells whose materials are `cellMaterial` (tetrahedra, then
/// hexahedra). `array` is the fibreArray(2) parameter; warns when it is set but no material reads
/// that direction; fails located when the mesh lacks it, has the wrong size, or a direction is zero.
FibreField resolveFibres(const core::Component& owner, int which, const core::Param<std::string>& array,
                         const MeshData* mesh, const std::vector<const materials::BaseMaterial*>& cellMaterial,
                         size_t tetrahedra);

} // namespace fascia::elements
