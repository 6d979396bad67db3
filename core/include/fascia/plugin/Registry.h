#pragma once
/// Component name -> creator, description, parameter docs and owning plugin.
#include "fascia/base/Component.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fascia::core {

struct ComponentEntry {
    std::string name;         ///< the XML tag
    std::string description;  ///< its first line: the summary --list prints; further lines: details for --describe
    std::string plugin;       ///< owning plugin id ("" for the core)
    std::string pluginFile;   ///< shared library it came from
    std::function<std::unique_ptr<Component>()> create;
};

class Registry {
public:
    static Registry& instance();

    /// Registers T under name; two plugins registering one name is an error naming both.
    template <class T> void add(const std::string& name, const std::string& description) {
        addEntry(ComponentEntry{name, description, m_currentPlugin, m_currentFile,
                                [] { return std::unique_ptr<Component>(new T()); }});
    }
    void addEntry(ComponentEntry e);
    /// Removes every entry of a plugin (when its loading failed half way).
    void removePlugin(const std::string& pluginId);

    const ComponentEntry* find(const std::string& name) const;
    std::vector<std::string> names() const;
    const std::map<std::string, ComponentEntry>& entries() const { return m_entries; }
    /// Creates a component with its class name set.
    std::unique_ptr<Component> create(const std::string& name) const;

    /// Set by the plugin manager while a plugin registers.
    void setCurrentPlugin(const std::string& id, const std::string& file) { m_currentPlugin = id; m_currentFile = file; }

    /// Component names that plugins not loaded (or not built) would provide: name -> plugin hint.
    void addKnownElsewhere(const std::string& component, const std::string& pluginHint);
    const std::string* knownElsewhere(const std::string& component) const;

private:
    std::map<std::string, ComponentEntry> m_entries;
    std::map<std::string, std::string> m_elsewhere;
    std::string m_currentPlugin, m_currentFile;
};

/// What `fascia-run --describe NAME` prints (and Python's help() on a component shows): the
/// component's plugin and description, then each parameter with its type, unit, default or
/// "required", range and help. An unknown name is an input error with the closest names.
std::string describeComponent(const std::string& name);

} // namespace fascia::core
