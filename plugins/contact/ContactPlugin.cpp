// fascia.contact: rigid tools and their contact with deformable bodies.
#include "fascia/plugin/Plugin.h"

#include "CapsuleTool.h"
#include "PlaneTool.h"
#include "SphereTool.h"
#include "SurfaceTool.h"

using namespace fascia::contact;

static void registerContact(fascia::core::Registry& r) {
    r.add<PlaneTool>("PlaneTool", "a rigid plane (half-space) touching a body's surface nodes, with optional Coulomb friction");
    r.add<SphereTool>("SphereTool", "a rigid sphere touching a body's surface nodes, with optional Coulomb friction");
    r.add<CapsuleTool>("CapsuleTool", "a rigid capsule (an instrument shaft with a rounded tip) touching a body's surface nodes");
    r.add<SurfaceTool>("SurfaceTool", "a rigid closed triangle surface (STL or OBJ: a retractor, a probe) touching a body's surface nodes, by a signed distance grid");
}

FASCIA_PLUGIN("fascia.contact", "0.1.0", "rigid tools, contact with a body's surface and the force on each tool", registerContact)
