// An out-of-tree plugin: a force field of its own, registered through the one entry point.
#include "fascia/plugin/Plugin.h"
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

namespace example {

/// Viscous drag f = -c v on every node: the smallest useful force field.
class ViscousDrag : public fascia::core::BaseForceField {
public:
    void addForce(fascia::core::BaseMechanicalState& s, fascia::Positions& f, double) override {
        const double c = m_coefficient.get();
        for (size_t i = 0; i < f.size(); ++i) f[i] -= c * s.v()[i];
    }

    fascia::core::Param<double> m_coefficient{this, fascia::core::ParamSpec("coefficient").unit("N s/m").min(0).help("drag coefficient c"), 1.0};
};

} // namespace example

static void registerExample(fascia::core::Registry& r) {
    r.add<example::ViscousDrag>("ViscousDrag", "viscous drag f = -c v (example out-of-tree plugin)");
}

FASCIA_PLUGIN("example.drag", "1.0.0", "an example out-of-tree plugin", registerExample)
