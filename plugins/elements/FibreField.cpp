#include "fascia/elements/FibreField.h"
#include "fascia/base/Format.h"

#include <cmath>

namespace fascia::elements {

using materials::BaseMaterial;
using core::formatNumber;

namespace {

/// The cell array a fibre parameter names, checked against the cell count.
const std::vector<double>* cellArray(const core::Component& owner, const core::Param<std::string>& p, const MeshData* mesh,
                                     size_t cells) {
    if (!p.isSet() || p.get().empty()) return nullptr;
    if (!mesh) owner.fail(p, "'" + p.name() + "' names a cell array of a mesh: give mesh=\"@loader.mesh\"");
    auto it = mesh->cellArrays.find(p.get());
    if (it == mesh->cellArrays.end()) {
        std::vector<std::string> names;
        std::string all;
        for (const auto& kv : mesh->cellArrays) {
            names.push_back(kv.first);
            all += (all.empty() ? "" : ", ") + kv.first;
        }
        std::vector<std::string> notes;
        const auto close = core::closestMatches(p.get(), names);
        if (!close.empty()) notes.push_back("did you mean '" + close[0] + "'?");
        notes.push_back(all.empty() ? "the mesh has no cell arrays" : "cell arrays: " + all);
        owner.fail(p, p.name() + " = \"" + p.get() + "\": the mesh has no such cell array (no cell array '" + p.get() + "')", notes);
    }
    if (it->second.size() != 3 * cells)
        owner.fail(p, p.name() + " = \"" + p.get() + "\" has " + std::to_string(it->second.size()) +
                          " values, expected 3 per cell (" + std::to_string(3 * cells) + ")");
    return &it->second;
}

} // namespace

FibreField resolveFibres(const core::Component& owner, int which, const core::Param<std::string>& array, const MeshData* mesh,
                         const std::vector<const BaseMaterial*>& cellMaterial, size_t tetrahedra) {
    FibreField out;
    const unsigned bit = which == 0 ? BaseMaterial::UsesI4 : BaseMaterial::UsesI6;
    for (const BaseMaterial* m : cellMaterial) out.used = out.used || (m && (m->uses() & bit));
    const std::vector<double>* arr = cellArray(owner, array, mesh, cellMaterial.size());
    if (!out.used) {
        if (array.isSet()) owner.warn("'" + array.name() + "' is set but no material of this force field reads that fibre direction");
        return out;
    }
    out.perElement = arr != nullptr;
    out.dir.assign(cellMaterial.size(), Vec3::Zero());
    const char* what = which == 0 ? "fibre" : "second fibre";
    for (size_t c = 0; c < cellMaterial.size(); ++c) {
        const BaseMaterial* m = cellMaterial[c];
        if (!m || !(m->uses() & bit)) continue;
        Vec3 d;
        if (arr) {
            d = Vec3((*arr)[3 * c], (*arr)[3 * c + 1], (*arr)[3 * c + 2]);
        } else if (const Vec3* md = m->fibreDirection(which)) {
            d = *md;
        } else {
            owner.fail("material '" + m->name() + "' reads a " + what + " direction but gives none: set it on the material or give '" +
                       array.name() + "' (a mesh cell array)");
        }
        const double len = d.norm();
        if (!(len > 1e-12) || !std::isfinite(len)) {
            const std::string cell = c < tetrahedra ? "tetrahedron " + std::to_string(c) : "hexahedron " + std::to_string(c - tetrahedra);
            owner.fail(array, std::string(what) + " direction of " + cell + " has length " + formatNumber(len, 6) +
                                  ": directions must be non-zero");
        }
        out.dir[c] = d / len;
    }
    return out;
}

} // namespace fascia::elements
