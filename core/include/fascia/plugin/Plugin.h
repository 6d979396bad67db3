#pragma once
/// The one entry point a plugin exports. Use FASCIA_PLUGIN(...) in exactly one .cpp of a plugin.
#include "fascia/base/Abi.h"
#include "fascia/plugin/Registry.h"

/// Bumped whenever a change to the core breaks binary compatibility with built plugins.
/// 2: BaseIntegrator::stableTimeStep, BaseConstraint::prescribesMotion and BaseObserver::observeFinal
/// (new virtual functions) and the load-curve parameters.
/// 3: BaseTopology holds the boundary triangles (a new member), BaseVisualSurface.
/// 4: SourceLoc gained a byte offset (its size changed), Base::failOutput.
/// 5: BaseObserver::records, BaseStepBackend::fetch, push and wait (new virtual functions),
///    MechanicalGroup::firstBadStep.
/// 6: PluginInfo::build (how the plugin was compiled), EIGEN_MAX_ALIGN_BYTES fixed at 16, core::Error
///    holds the further errors of a scene (more(), unshown(): its size changed).
/// 7: NodalLoad::curved (a new virtual function), the step terms ExplicitScheme and AxisHold
///    (sim/StepTerms.h), core::formatNumber, core::invCbrt and fastLog (base/FastMath.h).
#define FASCIA_ABI_VERSION 7

namespace fascia::core {

/// What fascia_plugin_info() returns. abiVersion stays the first member forever, so that a
/// plugin of any ABI can be identified and refused without reading the rest.
struct PluginInfo {
    int abiVersion;
    const char* id;           ///< dotted id, e.g. "fascia.heml"
    const char* version;      ///< plugin version, e.g. "0.1.0"
    const char* description;  ///< one line
    void (*registerComponents)(Registry&);
    /// How the plugin was compiled (fascia/base/Abi.h): the loader refuses another Eigen alignment
    /// and warns about a plugin built without optimisation.
    BuildAbi build;
};

} // namespace fascia::core

#define FASCIA_PLUGIN_ENTRY_NAME "fascia_plugin_info"

/// FASCIA_PLUGIN("my.plugin", "1.0", "what it adds", registerFunction)
#define FASCIA_PLUGIN(ID, VERSION, DESCRIPTION, REGISTER_FN)                                       \
    extern "C" __attribute__((visibility("default"))) const ::fascia::core::PluginInfo*          \
    fascia_plugin_info() {                                                                        \
        static const ::fascia::core::PluginInfo info{FASCIA_ABI_VERSION, ID, VERSION, DESCRIPTION, \
                                                     REGISTER_FN, FASCIA_THIS_BUILD_ABI};         \
        return &info;                                                                             \
    }
