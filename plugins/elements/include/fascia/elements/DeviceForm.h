#pragma once
/// What an element force field hands to a step backend that runs its elements itself, on a device
/// (the GPU step, plugins/cuda: docs/design.md, section 4.7): the form of its element math, its
/// parameters, the material of each element, its fibre directions, its relaxation and the rest data
/// its precompute holds, all in input order. A force field that can run there implements
/// DeviceFormSource (TLEDForceField: plugins/tled/TLEDDeviceForm.cpp; HEMLForceField:
/// plugins/heml/HEMLDeviceForm.cpp); the backend finds it by dynamic_cast, as core::LayoutReport,
/// so that it reads no parameter by name and computes no rest data a second time.
#include "fascia/base/Component.h"
#include "fascia/base/Types.h"
#include "fascia/materials/Material.h"

#include <vector>

namespace fascia::elements {

/// An element force field's device form (DeviceFormSource::deviceForm). Arrays per element are in
/// the input order of their kind, the values of an element one after the other.
struct DeviceForm {
    /// The element math: TLED's (tetrahedra and uniform-strain hexahedra with hourglass control,
    /// TLED eq. (1)-(3)), HEML's edge form on tetrahedra (HEML eq. (12)-(13), (29), (C.1)-(C.4):
    /// fascia/elements/EdgeForm.h) or HEML's mass-spring mode (eq. (38): a spring per edge, no
    /// material).
    enum class Kind { TLED, Edges, Springs };
    Kind kind = Kind::TLED;
    double J0 = 0.4;        ///< the volume ratio below which the laws are linearised (HEML section 4.4)
    double hourglass = 0;   ///< TLED: kappa_HG of the hourglass stiffnesses hexK (0 for HEML)
    /// The elements (the force field's own lists; null where it has none of that kind).
    const Tetrahedra* tetrahedra = nullptr;
    const Hexahedra* hexahedra = nullptr;

    /// The material of each cell (tetrahedra, then hexahedra) as the force field assigned them
    /// (elements::assignMaterials); empty for Springs.
    std::vector<const materials::BaseMaterial*> cellMaterial;
    /// Where a material was named, for a located error: the material of the cells that no listed
    /// group takes (elements::defaultMaterial; null when none), and the force field's groupMaterials
    /// parameter when it is set (null otherwise).
    const materials::BaseMaterial* material = nullptr;
    const core::BaseParam* groupMaterials = nullptr;

    /// Fibre directions from a mesh cell array (fibreArray, fibreArray2, as elements::resolveFibres
    /// resolves them): whether some direction is per element; then fibre[w] (w = 0: a0, 1: b0) holds
    /// 3 numbers per cell (tetrahedra, then hexahedra), unit, (1 0 0) and (0 1 0) where the cell's
    /// material does not read it, and is empty where no material reads that direction. Without an
    /// array the directions are each material's own (BaseMaterial::fibreDirection). Kind::TLED only:
    /// HEML's fibres are in edgeW.
    bool fibresPerElement = false;
    std::vector<double> fibre[2];

    /// The Prony series the force field relaxes with, in the order it takes them: its
    /// viscoelastic::ViscoelasticProny components, given as the core's Component because the element
    /// layer does not include the viscoelastic library (docs/design.md, section 2); a backend that
    /// links it casts them.
    std::vector<const core::Component*> series;

    /// Kind::TLED, and the volumes of every kind:
    std::vector<double> tetDN;      ///< 9 per tetrahedron: dN_a/dX_i of nodes a = 1..3 at 3 (a - 1) + i (the rows of Dm^-1)
    std::vector<double> tetVolume;  ///< rest volume of each tetrahedron (m^3)
    std::vector<double> hexDN;      ///< 24 per hexahedron: the uniform-strain dN_a/dX_i at 3 a + i (elements::hexUniformStrain)
    std::vector<double> hexC;       ///< 12 per hexahedron: the hourglass vectors c_q at 3 q + i (elements::hexHourglassVectors)
    std::vector<double> hexVolume;  ///< rest volume of each hexahedron (m^3)
    std::vector<double> hexK;       ///< hourglass stiffness K of each hexahedron (N/m, elements::hexHourglassStiffness)
    /// Kind::Edges and Kind::Springs (elements::EdgeRest), per tetrahedron:
    std::vector<double> edgeV;        ///< 9: the rest edges V_a = X_a - X_0, component i of V_a at 3 (a - 1) + i
    std::vector<double> edgeInvDetV;  ///< 1 / det V (signed)
    std::vector<double> edgeG;        ///< 6: G = V^-1 V^-T (xx yy zz xy yz xz); Edges only
    /// 3: V^-1 a0 (w = 0), V^-1 b0 (w = 1); empty where no material reads that direction, zero where
    /// the element's material does not; Edges only
    std::vector<double> edgeW[2];
    /// 6 (edge q from node elements::edgeA(q) to edgeB(q)): each edge's share of the stiffness
    /// (N/m) and its rest length (m); Springs only
    std::vector<double> springK, springLength;
};

/// An element force field that can give its device form (DeviceForm) after init.
class DeviceFormSource {
public:
    virtual ~DeviceFormSource();
    /// Its form, from what its precompute holds; a located error (at the force field) where it has
    /// no form a backend can take.
    virtual void deviceForm(DeviceForm& out) const = 0;
};

} // namespace fascia::elements
