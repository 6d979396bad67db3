// fascia.mechanics: state, mass, integrators, constraints and loads.
#include "fascia/plugin/Plugin.h"

#include "CentralDifference.h"
#include "ConstantForce.h"
#include "DynamicRelaxation.h"
#include "ExplicitEuler.h"
#include "FixedConstraint.h"
#include "LoadCurve.h"
#include "LumpedMass.h"
#include "MechanicalObject.h"
#include "PrescribedDisplacement.h"
#include "SemiImplicitEuler.h"
#include "SurfacePressure.h"

using namespace fascia::mechanics;

static void registerMechanics(fascia::core::Registry& r) {
    r.add<MechanicalObject>("MechanicalObject", "positions, velocities, forces and reactions of a body's nodes");
    r.add<LumpedMass>("LumpedMass", "diagonal mass from a density or a total mass (HEML section 3.3)");
    r.add<SemiImplicitEuler>("SemiImplicitEuler", "semi-implicit Euler integration with Rayleigh damping (HEML eq. (32))");
    r.add<ExplicitEuler>("ExplicitEuler", "explicit Euler integration with Rayleigh damping (HEML eq. (31))");
    r.add<CentralDifference>("CentralDifference", "central-difference integration with Rayleigh damping (TLED section 2)");
    r.add<DynamicRelaxation>("DynamicRelaxation", "static solver: adaptive dynamic relaxation, one load step per step (Joldes, Wittek and Miller 2009)");
    r.add<FixedConstraint>("FixedConstraint", "fixes nodes in all or some directions (rollers, symmetry planes)");
    r.add<PrescribedDisplacement>("PrescribedDisplacement", "nodes follow a displacement times a load shape over time");
    r.add<ConstantForce>("ConstantForce", "a force on nodes, constant or scaled by a load curve");
    r.add<SurfacePressure>("SurfacePressure", "a follower pressure on boundary triangles and hexahedral faces");
    r.add<LoadCurve>("LoadCurve", "a load curve c(t) (tabulated, linear or smooth) that loads link to scale their value");
}

FASCIA_PLUGIN("fascia.mechanics", "0.1.0", "state, mass, integrators, constraints and loads", registerMechanics)
