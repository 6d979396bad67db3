#pragma once
/// Helpers for materials whose moduli can be given two ways (e.g. mu and kappa, or youngModulus
/// and poissonRatio).
#include "fascia/base/Component.h"

#include <vector>

namespace fascia::materials {

/// Checks that exactly one way of giving the moduli is complete: every parameter of `direct`
/// set and neither E nor nu, or E and nu set and none of `direct`. Fails located at the owner
/// (or at the offending parameter) otherwise: both ways, neither, or a way half given.
/// Returns true when E and nu are to be used.
bool useYoungPoisson(const core::Component& owner, const std::vector<const core::BaseParam*>& direct,
                     const core::BaseParam& E, const core::BaseParam& nu);

} // namespace fascia::materials

namespace fascia::materials {

/// mu and kappa from either mu and kappa or youngModulus and poissonRatio (see useYoungPoisson).
void resolveMuKappa(const core::Component& owner, const core::Param<double>& mu, const core::Param<double>& kappa,
                    const core::Param<double>& E, const core::Param<double>& nu, double& outMu, double& outKappa);

/// A unit vector from a direction parameter; fails located when it is (nearly) zero.
Vec3 unitDirection(const core::Component& owner, const core::Param<Vec3>& p);

} // namespace fascia::materials
