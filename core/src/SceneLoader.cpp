#include "fascia/scene/SceneLoader.h"
#include "fascia/base/ErrorList.h"
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

/// What one build keeps besides the graph: the errors found so far (the build goes on after each,
/// docs/design.md section 7) and what they broke, so that an error that follows from another (a link
/// to a component that could not be created, a missing parameter whose value was refused) is not
/// reported again.
struct Build {
    explicit Build(const ElementSpec& root) : errors({root.loc.file, 0}) {}
    ErrorList errors;
    size_t next = 0;                                  ///< the next element's index, in file order
    std::map<const Base*, size_t> elementOf;          ///< the element each node and component came from
    std::set<std::pair<const Base*, std::string>> badAttributes;  ///< attributes that were refused
    std::set<std::string> missingComponents;          ///< the names of the elements that made no component
    bool bad(const Base& b, const std::string& attribute) const { return badAttributes.count({&b, attribute}) > 0; }
    size_t orderOf(const Base& b) const {
        auto it = elementOf.find(&b);
        return it == elementOf.end() ? ErrorList::kLast : it->second;
    }
};

/// Sets one attribute of obj; an unknown attribute or a refused value is a located error.
void setAttribute(Base& obj, const ElementSpec& spec, const std::string& key, const std::string& value, bool allowLinks,
                  Build& b) {
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
    b.badAttributes.insert({&obj, key});  // until it is read
    // a node's parameters take values or links, as a component's (gravity="@g.direction",
    // gravityCurve="@ramp"), except its name
    if (!allowLinks && !value.empty() && value[0] == '@' && key == "name")
        throwInputError(spec.loc, obj.className() + ": attribute '" + key + "' cannot be a link");
    p->read(value, spec.loc);
    b.badAttributes.erase({&obj, key});
}

/// Sets every attribute of obj, each error kept and the attribute left as it was.
void setAttributes(Base& obj, const ElementSpec& spec, bool allowLinks, Build& b) {
    for (auto& [key, value] : spec.attributes)
        b.errors.attempt(b.orderOf(obj), [&] { setAttribute(obj, spec, key, value, allowLinks, b); });
}

void buildChildren(Node& node, const ElementSpec& spec, Build& b);

std::unique_ptr<Node> buildNode(const ElementSpec& spec, Build& b) {
    auto node = std::make_unique<Node>();
    node->setLoc(spec.loc);
    b.elementOf[node.get()] = b.next++;
    // name first, so that later errors name the node
    setAttributes(*node, spec, false, b);
    buildChildren(*node, spec, b);
    return node;
}

/// The component of an element, or the located error of an unknown tag, with the closest names.
std::unique_ptr<Component> createComponent(const ElementSpec& spec) {
    Registry& reg = Registry::instance();
    auto comp = reg.create(spec.tag);
    if (comp) return comp;
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

void buildComponent(Node& node, const ElementSpec& spec, Build& b) {
    const size_t at = b.next++;
    std::string name = spec.tag;  // (the name an unnamed one would get, as far as links go)
    for (auto& [k, v] : spec.attributes)
        if (k == "name") name = v;
    std::unique_ptr<Component> comp;
    if (!b.errors.attempt(at, [&] { comp = createComponent(spec); })) {
        b.missingComponents.insert(name);  // its attributes are not checked: no one knows what it takes
        return;
    }
    comp->setLoc(spec.loc);
    for (auto& [k, v] : spec.attributes)
        if (k == "name") comp->setName(v);
    b.errors.attempt(at, [&] {
        if (!spec.children.empty())
            throwInputError(spec.children.front().loc, "component <" + spec.tag + "> cannot hold elements; put <" +
                                                           spec.children.front().tag + "> in a <Node>");
    });
    Component& c = node.addComponent(std::move(comp));
    b.elementOf[&c] = at;
    setAttributes(c, spec, true, b);
}

/// A child node has a name, unique among its siblings, and none of the root's time settings.
void checkChildNode(const Node& node, const Node& n, const ElementSpec& spec, std::set<std::string>& names, Build& b) {
    const size_t at = b.orderOf(n);
    b.errors.attempt(at, [&] {
        if (n.name().empty() && !b.bad(n, "name")) throwInputError(spec.loc, "a <Node> needs a name");
    });
    for (const BaseParam* p : {static_cast<const BaseParam*>(&n.dt), static_cast<const BaseParam*>(&n.dtSafety),
                               static_cast<const BaseParam*>(&n.endTime)})
        b.errors.attempt(at, [&] {
            if (p->isSet() && !b.bad(n, p->name()))
                throwInputError(spec.loc, "Node '" + n.name() + "': " + p->name() +
                                              " belongs on the root node (it sets the time of the whole scene)");
        });
    b.errors.attempt(at, [&] {
        if (!n.name().empty() && !names.insert("node:" + n.name()).second)
            throwInputError(spec.loc, "two child nodes of '" + node.name() + "' are named '" + n.name() + "'");
    });
}

void buildChildren(Node& node, const ElementSpec& spec, Build& b) {
    std::set<std::string> names;
    for (auto& child : spec.children) {
        if (child.tag == "RequiredPlugin") continue;  // loaded before the build
        if (child.tag == "Node") {
            Node& n = node.addChild(buildNode(child, b));
            checkChildNode(node, n, child, names, b);
        } else {
            buildComponent(node, child, b);
        }
    }
    // unique component names among siblings (unnamed components get their class name, numbered)
    std::set<std::string> used;
    for (auto& c : node.components())
        b.errors.attempt(b.orderOf(*c), [&] {
            if (!c->name().empty() && !used.insert(c->name()).second)
                throwInputError(c->loc(), "two components of node '" + node.name() + "' are named '" + c->name() + "'");
        });
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

/// Resolves the link of one parameter of c (a component's, or a node's own, e.g. gravityCurve),
/// relative to node n. A link to an element that made no component is left unresolved without a
/// word: its element's error says what is wrong.
void resolveLink(Base* c, BaseParam* p, const Node& n, Node& root, const Build& b) {
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
        if (b.missingComponents.count(compPath.substr(compPath.rfind('/') + 1))) return;
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
        return;
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

/// Resolves every link of the scene, each error kept.
void resolveLinks(Node& root, Build& b) {
    auto linksOf = [&](Base* c, const Node& n) {
        for (BaseParam* p : c->params())
            if (!p->linkText().empty())
                b.errors.attempt(b.orderOf(*c), [&] { resolveLink(c, p, n, root, b); });
    };
    root.visit([&](const Node& n) {
        linksOf(const_cast<Node*>(&n), n);
        for (auto& c : n.components()) linksOf(c.get(), n);
    });
}

/// Every required parameter is set, except one whose value was refused (its own error says so).
void checkRequired(Node& root, Build& b) {
    root.visit([&](const Node& n) {
        for (auto& c : n.components())
            for (BaseParam* p : c->params())
                b.errors.attempt(b.orderOf(*c), [&] {
                    if (p->spec().isRequired && !p->isSet() && !b.bad(*c, p->name()))
                        c->fail("missing required parameter '" + p->name() + "'" +
                                (p->spec().helpText.empty() ? "" : " (" + p->spec().helpText + ")"));
                });
    });
}

/// Loads the plugins the scene names (<RequiredPlugin name="..."/>, anywhere in it), so that their
/// components exist before the build. Each one's error is kept; any stops the load after them, since
/// the components of a plugin that failed would all be unknown.
void loadRequiredPlugins(const ElementSpec& root) {
    PluginManager& pm = PluginManager::instance();
    pm.loadDefaultPlugins();
    std::vector<const ElementSpec*> required;
    collectRequiredPlugins(root, required);
    ErrorList errors({root.loc.file, 0});
    for (size_t i = 0; i < required.size(); ++i)
        errors.attempt(i, [&, r = required[i]] {
            std::string name;
            for (auto& [k, v] : r->attributes) {
                if (k == "name") name = v;
                else throwInputError(r->loc, "unknown attribute '" + k + "' of RequiredPlugin", {"RequiredPlugin takes: name"});
            }
            if (name.empty()) throwInputError(r->loc, "RequiredPlugin needs name=\"...\" (a plugin name or a path to its .so)");
            std::vector<std::string> dirs;
            if (!r->loc.file.empty() && r->loc.file[0] != '<') dirs.push_back(fs::path(r->loc.file).parent_path().string());
            pm.load(name, r->loc, dirs);
        });
    errors.throwIfAny();
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
    loadRequiredPlugins(root);
    if (root.tag != "Node")
        throwInputError(root.loc, "the root element is <" + root.tag + ">, expected <Node>",
                        {"a scene starts with <Node name=\"root\" dt=\"...\">"});
    // the build goes on after an error, so that one load reports every independent one; they are
    // thrown together at the end, in file order (the order of their elements)
    Build b(root);
    auto node = buildNode(root, b);
    if (node->name().empty()) node->setName("root");
    checkRequired(*node, b);
    resolveLinks(*node, b);
    b.errors.throwIfAny();
    return node;
}

} // namespace fascia::core
