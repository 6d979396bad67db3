#include "CoreTestSupport.h"

#include "fascia/base/ErrorList.h"

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

// ---- several errors in one (ErrorList) ------------------------------------------------------

TEST_CASE("An ErrorList keeps what fails, goes on, and throws nothing when nothing failed", "[Error][ErrorList]") {
    ErrorList list({"s.xml", 0});
    CHECK(list.attempt(0, [] {}));
    CHECK(list.empty());
    CHECK_NOTHROW(list.throwIfAny());
    CHECK_FALSE(list.attempt(0, [] { throwInputError({"s.xml", 2}, "bad"); }));
    CHECK(list.count() == 1);
    // one error is thrown as it was: nothing appended
    auto e = errorOf([&] { list.throwIfAny(); });
    REQUIRE(e);
    CHECK(std::string(e->what()) == "s.xml:2: error: bad");
    CHECK(e->count() == 1);
    CHECK(e->more().empty());
    // what is no core::Error is no input error to gather: it passes
    CHECK_THROWS_AS(list.attempt(0, [] { throw std::logic_error("bug"); }), std::logic_error);
}

TEST_CASE("Several errors are thrown as one, in order of their keys, the first one's kind and text first",
          "[Error][ErrorList]") {
    ErrorList list({"s.xml", 0});
    list.add(Error(ErrorKind::Input, {"s.xml", 9}, "late", {"a note"}), 9);
    list.add(Error(ErrorKind::Output, {"s.xml", 3}, "first"), 3);
    list.add(Error(ErrorKind::Input, {"s.xml", 3}, "second at 3"), 3);  // found after, kept after
    auto e = errorOf([&] { list.throwIfAny(); });
    REQUIRE(e);
    CHECK(e->count() == 3);
    CHECK(e->kind() == ErrorKind::Output);  // the first error's: it sets the exit code
    CHECK(e->message() == "first");
    REQUIRE(e->more().size() == 2);
    CHECK(e->more()[0].message() == "second at 3");
    CHECK(e->more()[1].notes() == std::vector<std::string>{"a note"});
    CHECK(std::string(e->what()) ==
          "s.xml:3: error: first\ns.xml:3: error: second at 3\ns.xml:9: error: late\ns.xml:9: note: a note");
}

TEST_CASE("An ErrorList shows at most kErrorsShown errors and counts the others", "[Error][ErrorList]") {
    const int n = GENERATE(int(kErrorsShown) + 1, 1030);  // (1030: past what the list keeps, still counted)
    ErrorList list({"s.xml", 0});
    for (int i = 0; i < n; ++i) list.add(Error(ErrorKind::Input, {"s.xml", i + 1}, "e" + std::to_string(i)), size_t(i));
    auto e = errorOf([&] { list.throwIfAny(); });
    REQUIRE(e);
    CHECK(e->count() == size_t(n));
    CHECK(e->more().size() == kErrorsShown - 1);
    CHECK(e->unshown() == size_t(n) - kErrorsShown);
    const std::string what = e->what();
    const std::string last = what.substr(what.rfind('\n') + 1);
    CHECK(last == (n == int(kErrorsShown) + 1 ? "s.xml: note: 1 more error not shown"
                                               : "s.xml: note: " + std::to_string(n - int(kErrorsShown)) + " more errors not shown"));
}

TEST_CASE("An error that stands for several is taken apart when it joins a list", "[Error][ErrorList]") {
    ErrorList inner({"a.xml", 0});
    for (int i = 1; i <= 3; ++i) inner.add(Error(ErrorKind::Input, {"a.xml", i}, "inner" + std::to_string(i)), size_t(i));
    auto nested = errorOf([&] { inner.throwIfAny(); });
    REQUIRE(nested);
    ErrorList outer({"b.xml", 0});
    outer.add(Error(ErrorKind::Input, {"b.xml", 1}, "outer"), 0);
    outer.add(*nested, 1);
    CHECK(outer.count() == 4);
    auto e = errorOf([&] { outer.throwIfAny(); });
    REQUIRE(e);
    REQUIRE(e->more().size() == 3);
    for (const Error& m : e->more()) CHECK(m.more().empty());
    CHECK(e->more()[2].message() == "inner3");
}
