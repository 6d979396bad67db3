#include "fascia/plugin/Registry.h"

#include <sstream>

namespace fascia::core {

Registry& Registry::instance() {
    static Registry r;
    return r;
}

namespace {
std::string origin(const ComponentEntry& e) {
    if (e.plugin.empty()) return "the core";
    return "plugin '" + e.plugin + "'" + (e.pluginFile.empty() ? std::string() : " (" + e.pluginFile + ")");
}
} // namespace

void Registry::addEntry(ComponentEntry e) {
    auto it = m_entries.find(e.name);
    if (it != m_entries.end()) {
        throwInputError({}, "component '" + e.name + "' is registered twice: by " + origin(it->second) + " and by " +
                                origin(e),
                        {"load only one of these plugins (check FASCIA_PLUGIN_PATH and <RequiredPlugin>), or rename "
                         "the component in your own plugin"});
    }
    m_entries.emplace(e.name, std::move(e));
}

void Registry::removePlugin(const std::string& pluginId) {
    for (auto it = m_entries.begin(); it != m_entries.end();)
        it = it->second.plugin == pluginId ? m_entries.erase(it) : std::next(it);
}

const ComponentEntry* Registry::find(const std::string& name) const {
    auto it = m_entries.find(name);
    return it == m_entries.end() ? nullptr : &it->second;
}

std::vector<std::string> Registry::names() const {
    std::vector<std::string> out;
    for (auto& [n, e] : m_entries) out.push_back(n);
    return out;
}

std::unique_ptr<Component> Registry::create(const std::string& name) const {
    auto* e = find(name);
    if (!e) return nullptr;
    auto c = e->create();
    c->setClassName(name);
    return c;
}

void Registry::addKnownElsewhere(const std::string& component, const std::string& pluginHint) {
    m_elsewhere[component] = pluginHint;
}

const std::string* Registry::knownElsewhere(const std::string& component) const {
    auto it = m_elsewhere.find(component);
    return it == m_elsewhere.end() ? nullptr : &it->second;
}

std::string describeComponent(const std::string& name) {
    const Registry& reg = Registry::instance();
    const ComponentEntry* e = reg.find(name);
    if (!e) {
        const auto close = closestMatches(name, reg.names());
        throwInputError({}, "no component '" + name + "'" + (close.empty() ? "" : "; did you mean '" + close[0] + "'?"));
    }
    auto c = reg.create(name);
    std::ostringstream out;
    out << name << " (plugin " << (e->plugin.empty() ? "core" : e->plugin) << "): " << e->description << "\n\n";
    out << "parameters:\n";
    for (BaseParam* p : c->params()) {
        const auto& s = p->spec();
        out << "  " << p->name() << "  [" << p->typeName();
        if (!s.unitText.empty()) out << ", " << s.unitText;
        out << "]";
        if (s.isRequired) out << " required";
        else if (s.isOutput) out << " output (link to it with \"@" << "name." << p->name() << "\")";
        else {
            auto d = p->defaultText();
            if (d.size() > 40) d = d.substr(0, 37) + "...";
            out << " default: " << (d.empty() ? "(none)" : d);
        }
        const auto r = s.rangeText();
        if (!r.empty()) out << "  range: " << r;
        out << "\n";
        if (!s.helpText.empty()) out << "      " << s.helpText << "\n";
    }
    return out.str();
}

} // namespace fascia::core
