/// A plugin claiming ABI 999: written by hand instead of FASCIA_PLUGIN, as a plugin built against
/// a future Fascia would look.
#include "fascia/plugin/Plugin.h"

namespace {
void registerNothing(fascia::core::Registry&) {}
} // namespace

extern "C" __attribute__((visibility("default"))) const fascia::core::PluginInfo* fascia_plugin_info() {
    static const fascia::core::PluginInfo info{999, "fascia.test.abi", "9.9.9", "built for another ABI", registerNothing,
                                               FASCIA_THIS_BUILD_ABI};
    return &info;
}
