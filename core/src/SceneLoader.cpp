#include "fascia/scene/SceneLoader.h"
#include "fascia/base/InputFile.h"
#include "fascia/plugin/PluginManager.h"
#include "fascia/plugin/Registry.h"

#include <tinyxml2.h>

#include <filesystem>
#include <map>
#include <set>

namespace fs = std::filesystem;

namespace fascia::core {

namespace {

std::string xmlProblem(const tinyxml2::XMLDocument& doc) {
    using namespace tinyxml2;
    switch (doc.ErrorID()) {
    case XML_ERROR_MISMATCHED_ELEMENT: return "XML syntax error: mismatched closing tag";
    case XML_ERROR_PARSING_ELEMENT: return "XML syntax error: malformed element";
    case XML_ERROR_PARSING_ATTRIBUTE: return "XML syntax error: malformed attribute (missing quotes or '=')";
    case XML_ERROR_PARSING_TEXT: return "XML syntax error: malformed text";
    case XML_ERROR_PARSING_COMMENT: return "XML syntax error: unterminated comment";
    case XML_ERROR_EMPTY_DOCUMENT: return "the scene is empty";
    case XML_ERROR_PARSING: return "XML syntax error";
    default: return std::string("XML syntax error (") + doc.ErrorName() + ")";
    }
}

/// What a scene may hold in all, includes expanded: an include tree that fans out (each file
/// including the next twice) grows as 2^depth, so the count of includes and the bytes read are bounded.
constexpr int kMaxIncludes = 1000;
constexpr std::uintmax_t kMaxSceneBytes = std::uintmax_t(256) << 20;

/// The state of one parse: the chain of files being included (for cycles) and what was read so far.
struct ParseState {
    std::vector<std::string> stack;
    int includes = 0;
    std::uintmax_t bytes = 0;
};

void convert(const tinyxml2::XMLElement* e, const std::string& file, ElementSpec& out, ParseState& state);

ElementSpec parseDocument(const std::string& text, const std::string& file, ParseState& state) {
    tinyxml2::XMLDocument doc;
    doc.Parse(text.c_str(), text.size());
    if (doc.Error()) throwInputError({file, std::max(1, doc.ErrorLineNum())}, xmlProblem(doc));
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (!root) throwInputError({file, 1}, "the scene has no root element", {"a scene starts with <Node name=\"root\">"});
    if (const tinyxml2::XMLElement* second = root->NextSiblingElement())
        throwInputError({file, second->GetLineNum()},
                        std::string("a second root element <") + second->Name() + "> after <" + root->Name() + "> (line " +
                            std::to_string(root->GetLineNum()) + "): a scene file has one root element",
                        {"put it inside the root <Node>"});
    ElementSpec spec;
    convert(root, file, spec, state);
    return spec;
}

/// A scene or include file: a regular file of at most kMaxSceneFileBytes. The top file's errors are
/// located at its line 1, an include's at its <include> line.
std::string readSceneFile(const std::string& path, const SourceLoc& from) {
    return readRegularFile(path, "scene file", kMaxSceneFileBytes, from.empty() ? SourceLoc{path, 1} : from);
}

void convert(const tinyxml2::XMLElement* e, const std::string& file, ElementSpec& out, ParseState& state) {
    out.tag = e->Name();
    out.loc = {file, e->GetLineNum()};
    for (auto* a = e->FirstAttribute(); a; a = a->Next()) out.attributes.emplace_back(a->Name(), a->Value());
    for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
        if (std::string(c->Name()) == "include") {
            const char* href = c->Attribute("href");
            SourceLoc here{file, c->GetLineNum()};
            if (!href || !*href) throwInputError(here, "<include> needs an href=\"file.xml\" attribute");
            for (auto* a = c->FirstAttribute(); a; a = a->Next())
                if (std::string(a->Name()) != "href")
                    throwInputError(here, std::string("unknown attribute '") + a->Name() + "' of <include>",
                                    {"<include> takes only href"});
            const std::string target = resolveScenePath(href, here);
            if (std::find(state.stack.begin(), state.stack.end(), target) != state.stack.end())
                throwInputError(here, "'" + target + "' includes itself (include cycle)");
            if (state.stack.size() > 32) throwInputError(here, "includes nested more than 32 deep");
            if (++state.includes > kMaxIncludes)
                throwInputError(here, "more than " + std::to_string(kMaxIncludes) + " includes in the scene",
                                {"does a file include another many times (each copy is read again)?"});
            const std::string text = readSceneFile(target, here);
            state.bytes += text.size();
            if (state.bytes > kMaxSceneBytes)
                throwInputError(here, "the scene, includes expanded, is more than " + std::to_string(kMaxSceneBytes) +
                                          " bytes", {"does a file include another many times (each copy is read again)?"});
            state.stack.push_back(target);
            ElementSpec inc = parseDocument(text, target, state);
            state.stack.pop_back();
            out.children.push_back(std::move(inc));
            continue;
        }
        out.children.emplace_back();
        convert(c, file, out.children.back(), state);
    }
}

void collectRequiredPlugins(const ElementSpec& s, std::vector<const ElementSpec*>& out) {
    if (s.tag == "RequiredPlugin") out.push_back(&s);
    for (auto& c : s.children) collectRequiredPlugins(c, out);
}

void setAttributes(Base& obj, const ElementSpec& spec, bool allowLinks) {
    std::set<std::string> seen;
    for (auto& [key, value] : spec.attributes) {
        // not findParam: an attribute sets the parameter, which read() records (ParamLog.h)
        BaseParam* p = nullptr;
        for (BaseParam* q : obj.params())
            if (q->name() == key) p = q;
        if (!p) {
            std::vector<std::string> notes;
            auto close = closestMatches(key, obj.paramNames());
            if (!close.empty()) {
                std::string s = "did you mean ";
                for (size_t i = 0; i < close.size(); ++i) s += (i ? " or '" : "'") + close[i] + "'";
                notes.push_back(s + "?");
            } else {
                std::string all;
                for (auto& n : obj.paramNames()) all += (all.empty() ? "" : ", ") + n;
                notes.push_back(obj.className() + " takes: " + all);
            }
            throwInputError(spec.loc, obj.className() + (obj.name().empty() ? "" : " '" + obj.name() + "'") +
                                          ": unknown attribute '" + key + "'",
                            notes);
        }
        // a node's parameters take values or links, as a component's (gravity="@g.direction",
        // gravityCurve="@ramp"), except its name
        if (!allowLinks && !value.empty() && value[0] == '@' && key == "name")
            throwInputError(spec.loc, obj.className() + ": attribute '" + key + "' cannot be a link");
        p->read(value, spec.loc);
    }
}

void buildChildren(Node& node, const ElementSpec& spec);

std::unique_ptr<Node> buildNode(const ElementSpec& spec) {
    auto node = std::make_unique<Node>();
    node->setLoc(spec.loc);
    // name first, so that later errors name the node
    setAttributes(*node, spec, false);
    buildChildren(*node, spec);
    return node;
}

void buildComponent(Node& node, const ElementSpec& spec) {
    Registry& reg = Registry::instance();
    auto comp = reg.create(spec.tag);
    if (!comp) {
        std::vector<std::string> notes;
        if (auto* hint = reg.knownElsewhere(spec.tag)) notes.push_back(*hint);
        auto close = closestMatches(spec.tag, reg.names());
        if (!close.empty()) {
            std::string s = "did you mean ";
            for (size_t i = 0; i < close.size(); ++i) s += (i ? " or '" : "'") + close[i] + "'";
            notes.push_back(s + "?");
        }
        if (notes.empty()) notes.push_back("`fascia-run --list` prints every component; a component of your own plugin needs <RequiredPlugin name=\"...\"/>");
        throwInputError(spec.loc, "unknown component '" + spec.tag + "'", notes);
    }
    comp->setLoc(spec.loc);
    for (auto& [k, v] : spec.attributes)
        if (k == "name") comp->setName(v);
    if (!spec.children.empty())
        throwInputError(spec.children.front().loc, "component <" + spec.tag + "> cannot hold elements; put <" +
                                                       spec.children.front().tag + "> in a <Node>");
    Component& c = node.addComponent(std::move(comp));
    setAttributes(c, spec, true);
}

void buildChildren(Node& node, const ElementSpec& spec) {
    std::set<std::string> names;
    for (auto& child : spec.children) {
        if (child.tag == "RequiredPlugin") continue;  // loaded before the build
        if (child.tag == "Node") {
            Node& n = node.addChild(buildNode(child));
            if (n.name().empty()) throwInputError(child.loc, "a <Node> needs a name");
            for (BaseParam* p : {static_cast<BaseParam*>(&n.dt), static_cast<BaseParam*>(&n.dtSafety),
                                 static_cast<BaseParam*>(&n.endTime)})
                if (p->isSet())
                    throwInputError(child.loc, "Node '" + n.name() + "': " + p->name() +
                                                   " belongs on the root node (it sets the time of the whole scene)");
            if (!names.insert("node:" + n.name()).second)
                throwInputError(child.loc, "two child nodes of '" + node.name() + "' are named '" + n.name() + "'");
        } else {
            buildComponent(node, child);
        }
    }
    // unique component names among siblings (unnamed components get their class name, numbered)
    std::set<std::string> used;
    for (auto& c : node.components())
        if (!c->name().empty() && !used.insert(c->name()).second)
            throwInputError(c->loc(), "two components of node '" + node.name() + "' are named '" + c->name() + "'");
    // the first free of Class, Class2, Class3, ...; names are only ever added, so the search for the
    // next one of a class resumes where the last one stopped (linear in the count, not quadratic)
    std::map<std::string, int> nextIndex;
    for (auto& c : node.components())
        if (c->name().empty()) {
            int& i = nextIndex.emplace(c->className(), 1).first->second;
            std::string n = i == 1 ? c->className() : c->className() + std::to_string(i);
            while (used.count(n)) n = c->className() + std::to_string(++i);
            used.insert(n);
            c->setName(n);
        }
}

std::vector<std::string> allComponentPaths(Node& root) {
    std::vector<std::string> out;
    root.visit([&](const Node& n) {
        for (auto& c : n.components()) out.push_back(c->name());
    });
    return out;
}

/// Resolves the links of one object's parameters (a component's, or a node's own, e.g. gravityCurve),
/// relative to node n.
void resolveLinksOf(Base* c, const Node& n, Node& root) {
            for (BaseParam* p : c->params()) {
                if (p->linkText().empty()) continue;
                const std::string link = p->linkText().substr(1);
                std::string compPath = link, field;
                if (!p->isComponentLink()) {
                    auto dot = link.rfind('.');
                    const auto slash = link.rfind('/');
                    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
                        c->fail(*p, p->name() + " = \"" + p->linkText() + "\" must link to a field: \"@component.field\"");
                    compPath = link.substr(0, dot);
                    field = link.substr(dot + 1);
                }
                Component* target = n.resolveComponent(compPath);
                if (!target) {
                    std::vector<std::string> notes;
                    auto close = closestMatches(compPath.substr(compPath.rfind('/') + 1), allComponentPaths(root));
                    for (auto& s : close) notes.push_back("did you mean '" + s + "'?");
                    c->fail(*p, p->name() + " = \"" + p->linkText() + "\" links to nothing: no component '" + compPath +
                                    "' from node '" + n.name() + "'",
                            notes);
                }
                if (target == c) c->fail(*p, p->name() + " links to its own component");
                p->setLinkTarget(target);
                if (p->isComponentLink()) {
                    auto* l = static_cast<BaseLink*>(p);
                    if (!l->setTarget(target))
                        c->fail(*p, p->name() + " = \"" + p->linkText() + "\" links to " + target->className() + " '" +
                                        target->name() + "', which is not a " + l->targetType());
                    continue;
                }
                BaseParam* src = target->findParam(field);
                if (!src) {
                    std::vector<std::string> notes;
                    for (auto& s : closestMatches(field, target->paramNames())) notes.push_back("did you mean '" + s + "'?");
                    c->fail(*p, p->name() + " = \"" + p->linkText() + "\" links to nothing: " + target->className() +
                                    " '" + target->name() + "' has no field '" + field + "'",
                            notes);
                }
                if (!p->canBindTo(*src))
                    c->fail(*p, p->name() + " (" + p->typeName() + ") cannot take " + target->className() + "." + field +
                                    " (" + src->typeName() + ")");
                p->bindTo(src);
            }
}

void resolveLinks(Node& root) {
    root.visit([&](const Node& n) {
        resolveLinksOf(const_cast<Node*>(&n), n, root);
        for (auto& c : n.components()) resolveLinksOf(c.get(), n, root);
    });
}

void checkRequired(Node& root) {
    root.visit([&](const Node& n) {
        for (auto& c : n.components())
            for (BaseParam* p : c->params())
                if (p->spec().isRequired && !p->isSet())
                    c->fail("missing required parameter '" + p->name() + "'" +
                            (p->spec().helpText.empty() ? "" : " (" + p->spec().helpText + ")"));
    });
}

} // namespace

ElementSpec parseSceneFile(const std::string& path) {
    ParseState state;
    state.stack.push_back(path);
    const std::string text = readSceneFile(path, {});
    state.bytes = text.size();
    return parseDocument(text, path, state);
}

ElementSpec parseSceneString(const std::string& xml, const std::string& virtualName, const std::string& baseDir) {
    std::string name = virtualName;
    if (baseDir != "." && !baseDir.empty()) name = (fs::path(baseDir) / name).string();
    ParseState state;
    state.stack.push_back(name);
    state.bytes = xml.size();
    return parseDocument(xml, name, state);
}

std::unique_ptr<Node> buildScene(const ElementSpec& root) {
    PluginManager& pm = PluginManager::instance();
    pm.loadDefaultPlugins();
    std::vector<const ElementSpec*> required;
    collectRequiredPlugins(root, required);
    for (auto* r : required) {
        std::string name;
        for (auto& [k, v] : r->attributes) {
            if (k == "name") name = v;
            else throwInputError(r->loc, "unknown attribute '" + k + "' of RequiredPlugin", {"RequiredPlugin takes: name"});
        }
        if (name.empty()) throwInputError(r->loc, "RequiredPlugin needs name=\"...\" (a plugin name or a path to its .so)");
        std::vector<std::string> dirs;
        if (!r->loc.file.empty() && r->loc.file[0] != '<') dirs.push_back(fs::path(r->loc.file).parent_path().string());
        pm.load(name, r->loc, dirs);
    }
    if (root.tag != "Node")
        throwInputError(root.loc, "the root element is <" + root.tag + ">, expected <Node>",
                        {"a scene starts with <Node name=\"root\" dt=\"...\">"});
    auto node = buildNode(root);
    if (node->name().empty()) node->setName("root");
    checkRequired(*node);
    resolveLinks(*node);
    return node;
}

} // namespace fascia::core
