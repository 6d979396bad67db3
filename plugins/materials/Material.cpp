#include "fascia/materials/Material.h"
#include "fascia/materials/Moduli.h"
#include "fascia/materials/Laws.h"

#include <cmath>

namespace fascia::materials {

double BaseMaterial::waveSpeed(double rho) const {
    return std::sqrt((bulkModulus() + 4.0 / 3.0 * shearModulus()) / rho);
}

namespace {
std::string quotedList(const std::vector<const core::BaseParam*>& ps) {
    std::string s;
    for (size_t i = 0; i < ps.size(); ++i) {
        if (i) s += (i + 1 == ps.size()) ? " and " : ", ";
        s += "'" + ps[i]->name() + "'";
    }
    return s;
}
} // namespace

bool useYoungPoisson(const core::Component& owner, const std::vector<const core::BaseParam*>& direct,
                     const core::BaseParam& E, const core::BaseParam& nu) {
    const std::string ways = "give either " + quotedList(direct) + ", or 'youngModulus' and 'poissonRatio'";
    size_t nDirect = 0;
    const core::BaseParam* firstSet = nullptr;
    const core::BaseParam* firstUnset = nullptr;
    for (auto* p : direct) {
        if (p->isSet()) {
            ++nDirect;
            if (!firstSet) firstSet = p;
        } else if (!firstUnset) {
            firstUnset = p;
        }
    }
    const bool anyE = E.isSet() || nu.isSet();
    if (nDirect > 0 && anyE) {
        const core::BaseParam& e = E.isSet() ? E : nu;
        owner.fail(e, "'" + e.name() + "' is given together with '" + firstSet->name() + "': " + ways + ", not both");
    }
    if (anyE) {
        if (!E.isSet()) owner.fail(nu, "'poissonRatio' is given without 'youngModulus': " + ways);
        if (!nu.isSet()) owner.fail(E, "'youngModulus' is given without 'poissonRatio': " + ways);
        return true;
    }
    if (nDirect == 0) owner.fail("no elastic moduli given: " + ways);
    if (firstUnset)
        owner.fail(*firstSet, "'" + firstSet->name() + "' is given without '" + firstUnset->name() + "': " + ways);
    return false;
}

} // namespace fascia::materials

namespace fascia::materials {

void resolveMuKappa(const core::Component& owner, const core::Param<double>& mu, const core::Param<double>& kappa,
                    const core::Param<double>& E, const core::Param<double>& nu, double& outMu, double& outKappa) {
    if (useYoungPoisson(owner, {&mu, &kappa}, E, nu)) {
        outMu = lameMu(E.get(), nu.get());
        outKappa = bulkFromE(E.get(), nu.get());
    } else {
        outMu = mu.get();
        outKappa = kappa.get();
    }
}

Vec3 unitDirection(const core::Component& owner, const core::Param<Vec3>& p) {
    const Vec3& d = p.get();
    const double n = d.norm();
    if (!(n > 1e-12)) owner.fail(p, "'" + p.name() + "' must be a non-zero vector (it is normalised)");
    return d / n;
}

} // namespace fascia::materials
