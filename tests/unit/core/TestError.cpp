#include "CoreTestSupport.h"

using namespace fascia::core;
using namespace fascia::testing;

TEST_CASE("A located error is formatted like a compiler message, notes on their own lines", "[Error]") {
    Error e(ErrorKind::Input, {"scenes/liver.xml", 42}, "HEMLForceField 'liverFF': poissonRatio = 0.52 is outside [0, 0.5)",
            {"did you mean 'youngModulus'?", "second note"});
    CHECK(std::string(e.what()) ==
          "scenes/liver.xml:42: error: HEMLForceField 'liverFF': poissonRatio = 0.52 is outside [0, 0.5)\n"
          "scenes/liver.xml:42: note: did you mean 'youngModulus'?\n"
          "scenes/liver.xml:42: note: second note");
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.loc().line == 42);
    CHECK(e.message() == "HEMLForceField 'liverFF': poissonRatio = 0.52 is outside [0, 0.5)");
    CHECK(e.notes().size() == 2);
}

TEST_CASE("An error without a location or without a line says so", "[Error]") {
    CHECK(Error::format({}, "plugin 'x' not found", {"build it"}) == "error: plugin 'x' not found\nnote: build it");
    CHECK(Error::format({"mesh.vtk", 0}, "bad header", {}) == "mesh.vtk: error: bad header");
    CHECK(SourceLoc{"a.xml", 3}.str() == "a.xml:3");
    CHECK(SourceLoc{"a.xml", 0}.str() == "a.xml");
    CHECK(SourceLoc{}.str().empty());
}

TEST_CASE("An error at a byte offset of a binary file is formatted file then byte then error", "[Error]") {
    CHECK(SourceLoc{"m.vtk", 0, 0}.str() == "m.vtk: byte 0");
    CHECK(SourceLoc{"m.vtk", 0, 123456789012}.str() == "m.vtk: byte 123456789012");
    CHECK(Error::format({"m.vtk", 0, 290}, "CELLS: too many", {"read by X"}) ==
          "m.vtk: byte 290: error: CELLS: too many\nm.vtk: byte 290: note: read by X");
}

TEST_CASE("throwInputError and throwSimulationError carry the kind that picks the exit code", "[Error]") {
    auto in = errorOf([] { throwInputError({"s.xml", 2}, "bad"); });
    REQUIRE(in);
    CHECK(in->kind() == ErrorKind::Input);
    CHECK(std::string(in->what()) == "s.xml:2: error: bad");
    auto sim = errorOf([] { throwSimulationError("[/root/ff] step 3: NaN"); });
    REQUIRE(sim);
    CHECK(sim->kind() == ErrorKind::Simulation);
    CHECK(std::string(sim->what()) == "error: [/root/ff] step 3: NaN");
}

TEST_CASE("editDistance counts insertions, deletions and substitutions, ignoring case", "[Error]") {
    CHECK(editDistance("", "") == 0);
    CHECK(editDistance("abc", "") == 3);
    CHECK(editDistance("", "abcd") == 4);
    CHECK(editDistance("kitten", "sitting") == 3);
    CHECK(editDistance("youngModulus", "youngmodulus") == 0);
    CHECK(editDistance("dt", "dT") == 0);
    CHECK(editDistance("poissonRatio", "poisonRatio") == 1);
}

TEST_CASE("closestMatches suggests near names best first and nothing far", "[Error]") {
    const std::vector<std::string> names{"youngModulus", "poissonRatio", "density", "MeshLoader", "dt"};
    CHECK(closestMatches("youngModulu", names) == std::vector<std::string>{"youngModulus"});
    CHECK(closestMatches("poisonRatio", names) == std::vector<std::string>{"poissonRatio"});
    CHECK(closestMatches("Mesh", names) == std::vector<std::string>{"MeshLoader"});
    CHECK(closestMatches("zzzzzzzz", names).empty());
    CHECK(closestMatches("DENSITY", names) == std::vector<std::string>{"density"});
    // at most max, best first
    const std::vector<std::string> many{"abcd", "abce", "abcf", "abxx", "abcd2"};
    auto m = closestMatches("abcd", many, 2);
    REQUIRE(m.size() == 2);
    CHECK(m[0] == "abcd");
}
