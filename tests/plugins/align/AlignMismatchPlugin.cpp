/// A plugin whose PluginInfo records another Eigen alignment (32 bytes, AVX's default) than the
/// core's 16: written by hand instead of FASCIA_PLUGIN, because fascia/base/Abi.h refuses to
/// compile a unit that sees another alignment. It stands for a plugin whose build went around the
/// headers' check (its own definition of the info, another install of Fascia), which the loader
/// must refuse before any of its components can pass an Eigen type across.
#include "fascia/plugin/Plugin.h"

namespace {
void registerNothing(fascia::core::Registry&) {}
} // namespace

extern "C" __attribute__((visibility("default"))) const fascia::core::PluginInfo* fascia_plugin_info() {
    static const fascia::core::PluginInfo info{FASCIA_ABI_VERSION, "fascia.test.align", "0.0.1",
                                               "built with another Eigen alignment", registerNothing,
                                               fascia::core::BuildAbi{32, 32, 1}};
    return &info;
}
