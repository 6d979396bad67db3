#pragma once
// Helpers shared by the contact plugin's tests: block scenes touched by a tool, and access to the
// tools and states of a simulation.
#include "RigidTool.h"
#include "fascia/base/Error.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <optional>
#include <string>

namespace contacttest {

using fascia::Positions;
using fascia::Vec3;
using fascia::contact::RigidTool;
using fascia::core::Simulation;

/// A block [0,a]x[0,a]x[0,h] of neo-Hookean tissue (mu 1 kPa, kappa 5 kPa, 1000 kg/m^3) in node
/// "block" with the given integrator, force field, element split and extra components; the root
/// holds `root` (tools, attributes go in rootAttrs).
inline std::string blockScene(const std::string& integrator, const std::string& blockExtra, const std::string& root,
                              const std::string& rootAttrs = "dt=\"auto\"", const std::string& resolution = "4 4 2",
                              const std::string& forceField = "HEMLForceField", const std::string& element = "tetrahedra6",
                              double a = 0.1, double h = 0.05) {
    return "<Node name=\"root\" " + rootAttrs + ">\n" + root +
           "  <Node name=\"block\">\n"
           "    <GridMesh name=\"grid\" min=\"0 0 0\" max=\"" + std::to_string(a) + " " + std::to_string(a) + " " +
           std::to_string(h) + "\" resolution=\"" + resolution + "\" element=\"" + element + "\"/>\n"
           "    <MechanicalObject name=\"state\"/>\n"
           "    <LumpedMass density=\"1000\"/>\n"
           "    <NeoHookean name=\"mat\" mu=\"1000\" kappa=\"5000\"/>\n"
           "    <" + forceField + " name=\"ff\"/>\n"
           "    " + integrator + "\n" + blockExtra +
           "  </Node>\n"
           "</Node>\n";
}

inline RigidTool& toolOf(Simulation& sim, const std::string& name) {
    auto* t = dynamic_cast<RigidTool*>(&sim.tool(name));
    REQUIRE(t);
    return *t;
}

/// The message of the error building the scene throws ("" when none).
inline std::string errorOf(const std::string& xml) {
    try {
        Simulation::fromString(xml, "scene.xml");
    } catch (const fascia::core::Error& e) {
        return e.what();
    }
    return "";
}

inline Vec3 sum(const Positions& p) {
    Vec3 s = Vec3::Zero();
    for (const Vec3& v : p) s += v;
    return s;
}

} // namespace contacttest
