#include "fascia/plugin/PluginManager.h"
#include "fascia/plugin/Plugin.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace fascia::core {

PluginManager& PluginManager::instance() {
    static PluginManager m;
    return m;
}

std::string PluginManager::builtinPluginDir() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&PluginManager::builtinPluginDir), &info) && info.dli_fname) {
        fs::path lib = fs::weakly_canonical(fs::path(info.dli_fname));
        return (lib.parent_path() / FASCIA_PLUGIN_RELDIR).string();
    }
    return {};
}

std::vector<std::string> PluginManager::envPluginDirs() {
    std::vector<std::string> out;
    const char* env = std::getenv("FASCIA_PLUGIN_PATH");
    if (!env) return out;
    std::string cur;
    for (const char* p = env;; ++p) {
        if (*p == ':' || *p == '\0') {
            if (!cur.empty()) out.push_back(cur);
            cur.clear();
            if (*p == '\0') break;
        } else {
            cur.push_back(*p);
        }
    }
    return out;
}

namespace {
std::vector<std::string> sharedLibrariesIn(const std::string& dir) {
    std::vector<std::string> out;
    std::error_code ec;
    if (dir.empty() || !fs::is_directory(dir, ec)) return out;
    for (auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file() && e.path().extension() == ".so") out.push_back(e.path().string());
    std::sort(out.begin(), out.end());
    return out;
}
} // namespace

void PluginManager::loadDefaultPlugins() {
    if (m_defaultsLoaded) return;
    m_defaultsLoaded = true;
    for (auto& f : sharedLibrariesIn(builtinPluginDir())) loadFile(f);
    for (auto& d : envPluginDirs()) {
        std::error_code ec;
        if (!fs::is_directory(d, ec))
            throwInputError({"FASCIA_PLUGIN_PATH", 0}, "'" + d + "' is not a folder",
                            {"set FASCIA_PLUGIN_PATH to a colon-separated list of folders holding plugins"});
        for (auto& f : sharedLibrariesIn(d)) loadFile(f);
    }
    // the GPU step is a plugin that builds without the CUDA toolkit leave out: say so where a scene asks for it
    if (!Registry::instance().find("CudaStep"))
        Registry::instance().addKnownElsewhere(
            "CudaStep", "CudaStep is the cuda plugin's (fascia.cuda), which this build does not have: it is built only where "
                        "CMake finds the CUDA toolkit (option FASCIA_WITH_CUDA); without it the scene runs on the CPU");
}

const LoadedPlugin& PluginManager::load(const std::string& name, const SourceLoc& loc,
                                        const std::vector<std::string>& extraDirs) {
    for (auto& p : m_plugins)
        if (p.id == name) return p;
    std::vector<std::string> dirs = extraDirs;
    dirs.push_back(builtinPluginDir());
    for (auto& d : envPluginDirs()) dirs.push_back(d);

    std::vector<std::string> candidates;
    const bool looksLikePath = name.find('/') != std::string::npos || fs::path(name).extension() == ".so";
    if (looksLikePath) {
        if (fs::path(name).is_absolute()) candidates.push_back(name);
        else
            for (auto& d : dirs) candidates.push_back((fs::path(d) / name).lexically_normal().string());
    } else {
        std::string underscored = name;
        std::replace(underscored.begin(), underscored.end(), '.', '_');
        for (auto& d : dirs)
            for (auto& f : {name + ".so", "lib" + name + ".so", "lib" + underscored + ".so",
                            "libfascia_" + underscored + ".so"})
                candidates.push_back((fs::path(d) / f).string());
    }
    for (auto& c : candidates) {
        std::error_code ec;
        if (fs::is_regular_file(c, ec)) return loadFile(c, loc);
    }
    for (auto& c : candidates) {
        std::error_code ec;
        if (fs::exists(c, ec))
            throwInputError(loc, "plugin '" + name + "' is '" + c + "', which is " +
                                     (fs::is_directory(c, ec) ? "a folder" : "no regular file") + ", not a shared library");
    }
    std::string searched;
    for (auto& d : dirs) searched += (searched.empty() ? "" : ", ") + d;
    throwInputError(loc, "plugin '" + name + "' not found (searched " + searched + ")",
                    {"build the plugin, give its path, or add its folder to FASCIA_PLUGIN_PATH"});
}

BuildAbi coreBuildAbi() { return FASCIA_THIS_BUILD_ABI; }

namespace {

/// Refuses a plugin compiled with another Eigen alignment than the core (its Eigen types would have
/// another layout: fascia/base/Abi.h) and warns about one compiled without optimisation while the
/// core was (an out-of-tree build without CMAKE_BUILD_TYPE runs its loops tens of times slower).
void checkBuild(const PluginInfo& info, void* handle, const std::string& file, const SourceLoc& loc) {
    const BuildAbi core = coreBuildAbi();
    const bool dynamicDiffers = info.build.eigenMaxAlignBytes != core.eigenMaxAlignBytes;
    if (dynamicDiffers || info.build.eigenMaxStaticAlignBytes != core.eigenMaxStaticAlignBytes) {
        const char* name = dynamicDiffers ? "EIGEN_MAX_ALIGN_BYTES" : "EIGEN_MAX_STATIC_ALIGN_BYTES";
        const int seen = dynamicDiffers ? info.build.eigenMaxAlignBytes : info.build.eigenMaxStaticAlignBytes;
        const int ours = dynamicDiffers ? core.eigenMaxAlignBytes : core.eigenMaxStaticAlignBytes;
        dlclose(handle);
        throwInputError(loc, "plugin '" + file + "' was built with " + name + "=" + std::to_string(seen) + ", Fascia with " +
                                 std::to_string(ours) + ": Eigen types would have another layout in the plugin than in the core",
                        {"rebuild the plugin with Fascia's compile definitions: link Fascia::fascia_core "
                         "(fascia_add_plugin does), or use `pkg-config --cflags fascia`"});
    }
    if (core.optimised && !info.build.optimised) {
        std::cerr << (loc.empty() ? file : loc.str()) << ": warning: plugin '" << file
                  << "' was built without optimisation: its components may run tens of times slower; rebuild it "
                     "with -DCMAKE_BUILD_TYPE=Release (or -O2)\n";
    }
}

} // namespace

const LoadedPlugin& PluginManager::loadFile(const std::string& file, const SourceLoc& loc) {
    std::error_code ec;
    const std::string canon = fs::weakly_canonical(fs::path(file), ec).string();
    for (auto& p : m_plugins)
        if (p.file == canon) return p;
    if (!fs::is_regular_file(file, ec))
        throwInputError(loc, "plugin file '" + file + "' does not exist",
                        {"check the path, or build the plugin first"});

    void* h = dlopen(canon.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char* err = dlerror();
        throwInputError(loc, "cannot load plugin '" + file + "': " + (err ? err : "unknown error"),
                        {"check that it is a shared library built for this machine and that its dependencies are installed"});
    }
    using EntryFn = const PluginInfo* (*)();
    auto entry = reinterpret_cast<EntryFn>(dlsym(h, FASCIA_PLUGIN_ENTRY_NAME));
    if (!entry) {
        dlclose(h);
        throwInputError(loc, "'" + file + "' is not a Fascia plugin: it exports no " FASCIA_PLUGIN_ENTRY_NAME "()",
                        {"add FASCIA_PLUGIN(id, version, description, registerFunction) to one .cpp file of the plugin"});
    }
    const PluginInfo* info = entry();
    if (!info) {
        dlclose(h);
        throwInputError(loc, "plugin '" + file + "': " FASCIA_PLUGIN_ENTRY_NAME "() returned nothing");
    }
    if (info->abiVersion != FASCIA_ABI_VERSION) {
        const int abi = info->abiVersion;
        dlclose(h);
        throwInputError(loc, "plugin '" + file + "' was built for ABI " + std::to_string(abi) + ", this is ABI " +
                                 std::to_string(FASCIA_ABI_VERSION) + ": rebuild it against Fascia " FASCIA_VERSION_STRING);
    }
    checkBuild(*info, h, file, loc);
    const std::string id = info->id ? info->id : "";
    if (id.empty() || !info->registerComponents) {
        dlclose(h);
        throwInputError(loc, "plugin '" + file + "' has an empty id or no register function");
    }
    for (auto& p : m_plugins)
        if (p.id == id)
            throwInputError(loc, "two plugins have the id '" + id + "': " + p.file + " and " + canon,
                            {"load only one of them (check FASCIA_PLUGIN_PATH)"});

    Registry& reg = Registry::instance();
    reg.setCurrentPlugin(id, canon);
    try {
        info->registerComponents(reg);
    } catch (const Error& e) {
        reg.removePlugin(id);
        reg.setCurrentPlugin("", "");
        // keep the library mapped: the registry may have copied nothing of it, but it costs nothing
        throw Error(e.kind(), loc.empty() ? e.loc() : loc, e.message(), e.notes());
    } catch (const std::exception& e) {
        reg.removePlugin(id);
        reg.setCurrentPlugin("", "");
        throwInputError(loc, "plugin '" + file + "' failed while registering its components: " + e.what());
    }
    reg.setCurrentPlugin("", "");
    m_plugins.push_back(LoadedPlugin{id, info->version ? info->version : "", info->description ? info->description : "",
                                     canon, h});
    return m_plugins.back();
}

} // namespace fascia::core
