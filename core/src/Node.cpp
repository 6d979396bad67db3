#include "fascia/scene/Node.h"
#include "fascia/base/Error.h"
#include "fascia/sim/StepTeam.h"

#include <unistd.h>

#include <filesystem>

namespace fascia::core {

Node::Node() { setClassName("Node"); }
Node::Node(const std::string& name) : Node() { setName(name); }
// (a block's late run of the step team may still read this scene's states and force fields:
// fascia/sim/StepTeam.h)
Node::~Node() { waitForLateTasks(); }

Node* Node::root() {
    Node* n = this;
    while (n->m_parent) n = n->m_parent;
    return n;
}

std::string Node::path() const {
    if (!m_parent) return "/" + name();
    return m_parent->path() + "/" + name();
}

Node& Node::addChild(std::unique_ptr<Node> child) {
    child->m_parent = this;
    m_children.push_back(std::move(child));
    return *m_children.back();
}

Node& Node::addChild(const std::string& name) { return addChild(std::make_unique<Node>(name)); }

Component& Node::addComponent(std::unique_ptr<Component> c) {
    c->m_node = this;
    if (c->className().empty()) c->setClassName(demangledTypeName(typeid(*c).name()));
    m_components.push_back(std::move(c));
    return *m_components.back();
}

Node* Node::child(const std::string& name) const {
    for (auto& c : m_children)
        if (c->name() == name) return c.get();
    return nullptr;
}

Component* Node::component(const std::string& name) const {
    for (auto& c : m_components)
        if (c->name() == name) return c.get();
    return nullptr;
}

Component* Node::findByName(const std::string& name) const {
    if (auto* c = component(name)) return c;
    for (auto& ch : m_children)
        if (auto* c = ch->findByName(name)) return c;
    return nullptr;
}

Component* Node::findUnique(const std::string& nameOrPath) const {
    if (nameOrPath.find('/') != std::string::npos) return resolveComponent(nameOrPath);
    Component* found = nullptr;
    int count = 0;
    visit([&](const Node& n) {
        if (Component* c = n.component(nameOrPath)) found = found ? found : c, ++count;
    });
    if (count > 1)
        throwInputError({}, "the name '" + nameOrPath + "' is ambiguous: " + std::to_string(count) +
                                " components have it; give a path such as '" + found->path() + "'");
    return found;
}

namespace {
std::vector<std::string> splitPath(const std::string& p) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : p) {
        if (c == '/') {
            if (!cur.empty()) parts.push_back(cur);
            cur.clear();
        } else {
            cur.push_back(c);
        }
    }
    if (!cur.empty()) parts.push_back(cur);
    return parts;
}
} // namespace

Node* Node::resolveNode(const std::string& path) const {
    const Node* n = this;
    auto parts = splitPath(path);
    size_t i = 0;
    if (!path.empty() && path[0] == '/') {
        n = const_cast<Node*>(this)->root();
        // "/rootName/..." and "/..." both start at the root
        if (!parts.empty() && parts[0] == n->name()) i = 1;
    }
    for (; i < parts.size(); ++i) {
        if (parts[i] == ".") continue;
        if (parts[i] == "..") {
            if (!n->m_parent) return nullptr;
            n = n->m_parent;
            continue;
        }
        n = n->child(parts[i]);
        if (!n) return nullptr;
    }
    return const_cast<Node*>(n);
}

Component* Node::resolveComponent(const std::string& path) const {
    auto slash = path.rfind('/');
    if (slash == std::string::npos) {
        for (const Node* n = this; n; n = n->m_parent)
            if (auto* c = n->component(path)) return c;
        return nullptr;
    }
    Node* n = resolveNode(path.substr(0, slash + (slash == 0 ? 1 : 0)));
    return n ? n->component(path.substr(slash + 1)) : nullptr;
}

void SceneContext::claimOutput(const std::string& path, const Base& who) {
    // every output stays inside the output folder: "../x" or an absolute path would write where
    // the user did not ask (compared lexically, on absolute normalised paths)
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path dir = fs::absolute(outputDir.empty() ? "." : outputDir, ec).lexically_normal();
    const fs::path rel = fs::absolute(path, ec).lexically_normal().lexically_relative(dir);
    const BaseParam* filename = who.findParam("filename");
    if (fs::path(path).filename().empty()) {
        const std::string msg = "writes '" + path + "', which names a folder, not a file";
        if (filename && filename->isSet()) who.fail(*filename, msg, {"give filename a file name, e.g. \"liver\""});
        who.fail(msg);
    }
    if (rel.empty() || *rel.begin() == ".." || *rel.begin() == ".") {
        const std::string msg = "writes '" + path + "', which is outside the output folder '" + outputDir + "'";
        const std::vector<std::string> notes{"output file names are relative to the output folder (fascia-run --output) "
                                             "and stay inside it: no absolute path, no '..'"};
        if (filename && filename->isSet()) who.fail(*filename, msg, notes);
        who.fail(msg, notes);
    }
    // the file must be creatable: its nearest existing folder is a folder this process may write into
    // (checked now, before anything is written; the folders below it are created at the first write)
    fs::path up = fs::path(path).parent_path();
    while (!up.empty() && !fs::exists(up, ec)) up = up.parent_path();
    if (!up.empty() && !fs::is_directory(up, ec))
        who.failOutput(filename, "cannot write '" + path + "': '" + up.string() + "' is a file, not a folder");
    if (!up.empty() && ::access(up.c_str(), W_OK | X_OK) != 0)
        who.failOutput(filename, "cannot write '" + path + "': no permission to write into '" + up.string() + "'");
    const std::string me = who.path() + (who.loc().empty() ? "" : " (" + who.loc().str() + ")");
    auto [it, fresh] = outputs.emplace(path, me);
    if (!fresh && it->second != me)
        who.fail("writes '" + path + "', which " + it->second + " writes too",
                 {"give one of them another filename (or name)"});
}

SceneContext& Node::context() {
    Node* r = root();
    if (!r->m_context) r->m_context = std::make_unique<SceneContext>();
    return *r->m_context;
}

Vec3 Node::contextGravity() const {
    for (const Node* n = this; n; n = n->m_parent)
        if (n->gravity.isSet()) return n->gravity.get();
    return Vec3::Zero();
}

const Curve& Node::contextGravityCurve() const {
    for (const Node* n = this; n; n = n->m_parent)
        if (n->gravity.isSet()) return n->gravityCurve.get();
    return gravityCurve.get();  // unset: the constant 1 (no gravity to scale anyway)
}

} // namespace fascia::core
