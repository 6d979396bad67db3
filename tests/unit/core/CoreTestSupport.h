#pragma once
/// Helpers shared by the core tests: catching located errors, the test plugin, temporary folders.
#include "fascia/base/Error.h"
#include "fascia/plugin/PluginManager.h"
#include "fascia/scene/SceneLoader.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace fascia::testing {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

inline std::string testPluginFile(const std::string& kase, const std::string& lib) {
    return std::string(TEST_PLUGIN_DIR) + "/" + kase + "/" + lib;
}
inline std::string goodPluginFile() { return testPluginFile("good", "libfascia_testplugin.so"); }

/// Loads the built-in plugins and the good test plugin (idempotent: order of tests does not matter).
inline void loadTestPlugin() {
    auto& pm = core::PluginManager::instance();
    pm.loadDefaultPlugins();
    pm.loadFile(goodPluginFile());
}

/// The fascia::core::Error f throws, or nothing.
template <class F> std::optional<core::Error> errorOf(F&& f) {
    try {
        f();
    } catch (const core::Error& e) {
        return e;
    }
    return std::nullopt;
}

/// The error of building and initialising an inline scene; messages say "scene.xml:LINE".
inline std::optional<core::Error> sceneError(const std::string& xml) {
    loadTestPlugin();
    return errorOf([&] { core::Simulation::fromString(xml, "scene.xml"); });
}

inline std::unique_ptr<core::Simulation> scene(const std::string& xml) {
    loadTestPlugin();
    return core::Simulation::fromString(xml, "scene.xml");
}

/// The value of a component's parameter of type T.
template <class T> const T& paramOf(const core::Component& c, const std::string& name) {
    auto* p = dynamic_cast<const core::Param<T>*>(c.findParam(name));
    INFO("parameter " << name << " of " << c.path());
    REQUIRE(p != nullptr);
    return p->get();
}

template <class T> const T& paramOf(core::Simulation& sim, const std::string& comp, const std::string& name) {
    core::Component* c = sim.find(comp);
    INFO("component " << comp);
    REQUIRE(c != nullptr);
    return paramOf<T>(*c, name);
}

/// A fresh folder under the system temp folder, removed with everything in it.
class TempDir {
public:
    TempDir() {
        std::string tmpl = (fs::temp_directory_path() / "fascia-core-test-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
        m_path = fs::canonical(tmpl);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(m_path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return m_path; }
    /// Writes text into path()/rel (folders created); returns the full path.
    std::string write(const std::string& rel, const std::string& text) const {
        fs::path p = m_path / rel;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
        return p.string();
    }

private:
    fs::path m_path;
};

} // namespace fascia::testing
