#pragma once
/// Material assignment per mesh group: the `groupMaterials` parameter ("1 @soft tumour @stiff":
/// pairs of a group tag or name and a material path, the '@' optional) as a typed value, split into pairs once when
/// read, and resolved against the mesh and the scene by assignMaterials().
#include "fascia/base/Component.h"
#include "fascia/base/Param.h"
#include "fascia/materials/Material.h"

#include <string>
#include <utility>
#include <vector>

namespace fascia::elements {

/// The groupMaterials text split into (group, material path) pairs.
struct GroupMaterialList {
    GroupMaterialList() = default;
    GroupMaterialList(const std::string& text);  // NOLINT: set("1 @mat") reads like the XML
    GroupMaterialList(const char* text) : GroupMaterialList(std::string(text)) {}
    std::string text;                                      ///< as written
    std::vector<std::pair<std::string, std::string>> pairs;  ///< (group, "@path")
    bool odd = false;                                      ///< an unpaired word is left (reported at init)
    bool empty() const { return pairs.empty() && !odd; }
};

/// The element kinds a force field assigns materials to.
enum class ElementKind { Tetrahedron, Hexahedron };

/// What a force field needs to assign materials.
struct MaterialAssignment {
    std::vector<materials::BaseMaterial*> tetrahedra, hexahedra;  ///< per element, input order
};

/// The material of every element: the group's when groupMaterials lists its group (tags from the
/// mesh, all 0 without one), else `fallback` (the force field's `material`, or without
/// groupMaterials the material in its context). Input errors are located at the parameter.
MaterialAssignment assignMaterials(const core::Component& owner, const core::Param<GroupMaterialList>& groups,
                                   materials::BaseMaterial* fallback, const MeshData* mesh, size_t tetrahedra,
                                   size_t hexahedra);

/// The materials groupMaterials names (for dependencies(): initialised before the force field).
std::vector<materials::BaseMaterial*> listedMaterials(const core::Component& owner, const core::Param<GroupMaterialList>& groups);

/// The default material of a force field: `material` when set, else (without groupMaterials) the
/// material in the owner's context; null when none.
materials::BaseMaterial* defaultMaterial(const core::Component& owner, const core::Link<materials::BaseMaterial>& material,
                                         const core::Param<GroupMaterialList>& groups);

} // namespace fascia::elements

namespace fascia::core {
template <>
struct ParamTraits<elements::GroupMaterialList> {
    static const char* typeName() { return "group material pairs"; }
    static bool parse(const std::string& text, elements::GroupMaterialList& out, std::string&) {
        out = elements::GroupMaterialList(text);
        return true;
    }
    static std::string format(const elements::GroupMaterialList& v) { return v.text; }
    static std::string check(const elements::GroupMaterialList&, const ParamSpec&) { return {}; }
};
} // namespace fascia::core
