#include "fascia/elements/GroupMaterials.h"

#include "fascia/scene/Node.h"

#include <map>
#include <sstream>

namespace fascia::elements {

using materials::BaseMaterial;

GroupMaterialList::GroupMaterialList(const std::string& t) : text(t) {
    std::istringstream is(t);
    std::vector<std::string> words;
    for (std::string w; is >> w;) words.push_back(w);
    for (size_t i = 0; i + 1 < words.size(); i += 2) pairs.emplace_back(words[i], words[i + 1]);
    odd = words.size() % 2 == 1;
}

namespace {

const char* kForm = "give pairs of a group (tag number or name) and a material path, e.g. \"1 @liver 2 @vessel\"";

/// A material path with or without its leading '@' ("@liver" or "liver").
std::string pathOf(const std::string& raw) { return !raw.empty() && raw[0] == '@' ? raw.substr(1) : raw; }

/// The material a pair names; fails located at the parameter.
BaseMaterial* resolve(const core::Component& owner, const core::Param<GroupMaterialList>& p, const std::string& key,
                      const std::string& raw) {
    const std::string path = pathOf(raw);
    if (path.empty()) owner.fail(p, "'" + raw + "' (for group " + key + ") is not a material path: " + kForm);
    core::Component* c = owner.node() ? owner.node()->resolveComponent(path) : nullptr;
    if (!c)
        owner.fail(p, "groupMaterials: no component '" + raw + "' for group " + key + " (no component '" + path +
                          "' is found from this node)");
    auto* m = dynamic_cast<BaseMaterial*>(c);
    if (!m) owner.fail(p, "groupMaterials: '" + raw + "' (for group " + key + ") is a " + c->className() + ", not a material");
    return m;
}

/// The tag of a group given by number or by name.
int tagOf(const core::Component& owner, const core::Param<GroupMaterialList>& p, const std::string& key, const MeshData* mesh) {
    char* end = nullptr;
    const long tag = std::strtol(key.c_str(), &end, 10);
    if (!key.empty() && end && *end == 0) return static_cast<int>(tag);
    std::vector<std::string> names;
    if (mesh)
        for (const auto& [t, name] : mesh->groupNames) {
            if (name == key) return t;
            names.push_back(name);
        }
    std::vector<std::string> notes;
    const auto close = core::closestMatches(key, names);
    if (!close.empty()) notes.push_back("did you mean '" + close[0] + "'?");
    else if (!names.empty()) {
        std::string all;
        for (auto& n : names) all += (all.empty() ? "" : ", ") + n;
        notes.push_back("group names: " + all);
    }
    owner.fail(p, "groupMaterials: '" + key + "' is neither a group tag nor a group name of the mesh", notes);
}

} // namespace

BaseMaterial* defaultMaterial(const core::Component& owner, const core::Link<BaseMaterial>& material,
                              const core::Param<GroupMaterialList>& groups) {
    if (material.get()) return material.get();
    if (groups.isSet() && !groups.get().empty()) return nullptr;
    return owner.node() ? owner.node()->findInContext<BaseMaterial>() : nullptr;
}

std::vector<BaseMaterial*> listedMaterials(const core::Component& owner, const core::Param<GroupMaterialList>& groups) {
    std::vector<BaseMaterial*> out;
    if (!owner.node()) return out;
    for (const auto& [key, raw] : groups.get().pairs)
        if (!pathOf(raw).empty())
            if (auto* m = dynamic_cast<BaseMaterial*>(owner.node()->resolveComponent(pathOf(raw)))) out.push_back(m);
    return out;
}

MaterialAssignment assignMaterials(const core::Component& owner, const core::Param<GroupMaterialList>& groups,
                                   BaseMaterial* fallback, const MeshData* mesh, size_t nTets, size_t nHexes) {
    const GroupMaterialList& list = groups.get();
    if (list.odd)
        owner.fail(groups, "groupMaterials = \"" + list.text + "\" is not a list of pairs: " + kForm);
    std::map<int, BaseMaterial*> byTag;
    for (const auto& [key, raw] : list.pairs) {
        const int tag = tagOf(owner, groups, key, mesh);
        BaseMaterial* m = resolve(owner, groups, key, raw);
        if (byTag.count(tag)) owner.fail(groups, "groupMaterials: group " + key + " is given twice");
        byTag[tag] = m;
    }
    if (byTag.empty() && !fallback)
        owner.fail("no material: add one (e.g. <NeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>) to the node, "
                   "set material=\"@name\", or give groupMaterials");
    MaterialAssignment out;
    const auto fill = [&](size_t n, const std::vector<int>* tags, const char* kind, std::vector<BaseMaterial*>& dst) {
        dst.resize(n);
        for (size_t e = 0; e < n; ++e) {
            const int tag = tags && e < tags->size() ? (*tags)[e] : 0;
            auto it = byTag.find(tag);
            BaseMaterial* m = it != byTag.end() ? it->second : fallback;
            if (!m)
                owner.fail(groups, std::string("no material for ") + kind + " " + std::to_string(e) + " of group " +
                                       std::to_string(tag) + ": list the group in groupMaterials or set material=\"@...\"");
            dst[e] = m;
        }
    };
    fill(nTets, mesh ? &mesh->tetrahedronGroup : nullptr, "tetrahedron", out.tetrahedra);
    fill(nHexes, mesh ? &mesh->hexahedronGroup : nullptr, "hexahedron", out.hexahedra);
    return out;
}

} // namespace fascia::elements
