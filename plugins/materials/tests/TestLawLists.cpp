// Every list of laws follows the one type list (materials/BuiltinMaterials.h): a law added there
// must have its section in docs/materials.md, its tag and parameters in the fuzz dictionary
// (tests/fuzz/dict/scene.dict), and its registry description built from its parts
// (materials/ComposedLaw.h). The scene dump (tests/regression/SceneDump.cpp) takes its laws from
// the list itself.
#include "fascia/materials/BuiltinMaterials.h"
#include "fascia/plugin/PluginManager.h"
#include "fascia/plugin/Registry.h"

#include <catch2/catch.hpp>

#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace fascia;

namespace {

std::string readSource(const std::string& relative) {
    std::ifstream in(std::string(FASCIA_SOURCE_DIR) + "/" + relative);
    REQUIRE(in);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The names in the "### " headings of a markdown text, before any parenthesis, split at every
/// character that cannot be part of a name ("### IncompressibleNeoHookean, IncompressibleMooneyRivlin
/// (HEML Table 3)" names two laws).
std::set<std::string> headingWords(const std::string& md) {
    std::set<std::string> out;
    std::istringstream in(md);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("### ", 0) != 0) continue;
        const std::string names = line.substr(4, line.find('(', 4) - 4);  // (npos - 4: to the end)
        std::string word;
        for (char c : names + " ") {
            if (std::isalnum(static_cast<unsigned char>(c))) word += c;
            else if (!word.empty()) out.insert(word), word.clear();
        }
    }
    return out;
}

/// The quoted entries of a libFuzzer dictionary.
std::set<std::string> dictionaryEntries(const std::string& dict) {
    std::set<std::string> out;
    std::istringstream in(dict);
    for (std::string line; std::getline(in, line);) {
        const size_t a = line.find('"'), b = line.rfind('"');
        if (line.empty() || line[0] == '#' || a == std::string::npos || b <= a) continue;
        std::string e;
        for (size_t i = a + 1; i < b; ++i) e += line[i] == '\\' && i + 1 < b ? line[++i] : line[i];
        out.insert(e);
    }
    return out;
}

/// The section of docs/materials.md whose "### " heading names `law` (up to the next heading).
std::string sectionOf(const std::string& md, const std::string& law) {
    std::istringstream in(md);
    std::string out;
    bool inside = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("#", 0) == 0) inside = line.rfind("### ", 0) == 0 && headingWords(line).count(law) == 1;
        if (inside) out += line + "\n";
    }
    return out;
}

} // namespace

TEST_CASE("every built-in law's section in docs/materials.md gives the energy the code computes", "[materials][docs]") {
    const std::string md = readSource("docs/materials.md");
    materials::forEachBuiltinMaterial([&](auto* tag) {
        using M = std::decay_t<decltype(*tag)>;
        CAPTURE(M::kName);
        // "W = " and the law's parts' kEnergy joined (ComposedLaw::energy), as --describe prints it
        CHECK_THAT(sectionOf(md, M::kName), Catch::Contains("W = " + M::LawType::energy()));
    });
}

TEST_CASE("every built-in law has its section in docs/materials.md", "[materials][docs]") {
    const std::set<std::string> sections = headingWords(readSource("docs/materials.md"));
    for (const std::string& law : materials::builtinMaterialNames()) {
        CAPTURE(law);
        CHECK(sections.count(law) == 1);
    }
    // the check can fail: a name no heading has
    CHECK(sections.count("NoSuchLaw") == 0);
}

TEST_CASE("the fuzz dictionary holds every built-in law's tag and parameter names", "[materials][fuzz]") {
    const std::set<std::string> dict = dictionaryEntries(readSource("tests/fuzz/dict/scene.dict"));
    REQUIRE(dict.count("<Node") == 1);
    for (const std::string& law : materials::builtinMaterialNames()) {
        CAPTURE(law);
        CHECK(dict.count("<" + law) == 1);
        const auto m = materials::createBuiltinMaterial(law);
        REQUIRE(m);
        for (const core::BaseParam* p : m->params()) {
            CAPTURE(p->name());
            CHECK(dict.count(p->name() + "=\"") == 1);
        }
    }
}

TEST_CASE("every built-in law's registry description is built from its isochoric and volumetric parts", "[materials]") {
    core::PluginManager::instance().load("fascia_materials");
    const auto& reg = core::Registry::instance();
    materials::forEachBuiltinMaterial([&](auto* tag) {
        using M = std::decay_t<decltype(*tag)>;
        using Law = typename M::LawType;
        CAPTURE(M::kName);
        const core::ComponentEntry* e = reg.find(M::kName);
        REQUIRE(e);
        const std::string W = Law::energy();
        const std::string vol = Law::Volumetric::kEnergy;  // "" for NoVolume; "-mu ln J ..." joined as " - mu ln J ..."
        CHECK_THAT(W, Catch::StartsWith(Law::Isochoric::kEnergy) && Catch::EndsWith(vol.empty() ? "" : vol.substr(1)));
        const size_t eol = e->description.find('\n');
        REQUIRE(eol != std::string::npos);
        CHECK(e->description.substr(0, eol) == std::string(M::kTitle) + ": " + W);
        CHECK_THAT(e->description.substr(eol + 1), Catch::StartsWith("W = " + W + ", " + M::kTerms));
        CHECK_THAT(e->description, Catch::Contains(std::string("isochoric ") + Law::Isochoric::kEnergy));
    });
}
