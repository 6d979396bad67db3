#pragma once
/// Loads plugins (shared libraries) at run time: the built-in folder, FASCIA_PLUGIN_PATH, and
/// <RequiredPlugin name="..."/>. Every failure is a clear error naming the file and what to do.
#include "fascia/base/Error.h"

#include <deque>
#include <string>
#include <vector>

namespace fascia::core {

struct LoadedPlugin {
    std::string id, version, description, file;
    void* handle = nullptr;
};

class PluginManager {
public:
    static PluginManager& instance();

    /// Loads every plugin of the built-in folder and of FASCIA_PLUGIN_PATH, once.
    void loadDefaultPlugins();
    /// Loads one plugin by file path or by name ("fascia_heml", "libfascia_heml.so", "heml", "fascia.heml"),
    /// searched in extraDirs, the built-in folder and FASCIA_PLUGIN_PATH. Already loaded: no-op.
    /// Errors are located at loc.
    const LoadedPlugin& load(const std::string& nameOrPath, const SourceLoc& loc = {},
                             const std::vector<std::string>& extraDirs = {});
    /// Loads a shared library file; errors name the file and what to do.
    const LoadedPlugin& loadFile(const std::string& file, const SourceLoc& loc = {});

    const std::deque<LoadedPlugin>& plugins() const { return m_plugins; }
    /// The folder built-in plugins live in: <dir of libfascia_core>/fascia/plugins.
    static std::string builtinPluginDir();
    /// Directories of FASCIA_PLUGIN_PATH (colon separated).
    static std::vector<std::string> envPluginDirs();

private:
    std::deque<LoadedPlugin> m_plugins;
    bool m_defaultsLoaded = false;
};

} // namespace fascia::core
