/// Checkpoint and restart in the core (Simulation::save / restore, fascia/base/StateIO.h): the records
/// and their checks, every way a checkpoint file can be wrong, a scene that is not the one that wrote
/// it, and the last good state of a failed step. The scenes use the test plugin (tests/plugins/good),
/// whose TestNaN saves its step counter.
#include "CoreTestSupport.h"

#include "fascia/base/StateIO.h"

#include <cmath>
#include <cstring>

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

/// One body: state, mass, integrator and TestNaN (a constant force, NaN at one step).
std::string body(const std::string& nanAttrs = "force=\"0 0 -1\"", const std::string& mass = "2") {
    return R"(<Node name="root" dt="0.01">
  <Node name="body">
    <TestEuler name="euler"/>
    <TestState name="state" position="0 0 0  1 0 0  0 1 0"/>
    <TestMass name="mass" mass=")" + mass + R"("/>
    <TestNaN name="nan" )" + nanAttrs + R"(/>
  </Node>
</Node>)";
}

std::string readAll(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeAll(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

/// The error of restoring `file` into a fresh simulation of `xml`.
std::optional<Error> restoreError(const std::string& xml, const fs::path& file) {
    auto sim = scene(xml);
    return errorOf([&] { sim->restore(file.string()); });
}

/// A checkpoint of body() after 3 steps.
std::string checkpointAfter3(const fs::path& file) {
    auto sim = scene(body());
    sim->run(3);
    sim->save(file.string());
    return readAll(file);
}

bool sameBits(const Positions& a, const Positions& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data()->data(), b.data()->data(), 24 * a.size()) == 0);
}

} // namespace

TEST_CASE("Records read back by name and size, and a mismatch names the record", "[StateWriter][StateReader]") {
    StateWriter w;
    w.beginSection("/root/a", "Thing");
    w.put("t", 1.5);
    w.put("n", 7L);
    w.put("on", true);
    w.put("label", std::string("abc"));
    const double v[3] = {1, 2, 3};
    w.put("v", v, 3);
    w.endSection();
    const std::string& b = w.bytes();
    SECTION("in order") {
        StateReader r(b, 0, b.size(), "f.ckpt");
        r.beginSection("/root/a", "Thing");
        CHECK(r.getDouble("t") == 1.5);
        CHECK(r.getLong("n") == 7);
        CHECK(r.getBool("on"));
        CHECK(r.getText("label") == "abc");
        CHECK(r.getDoubles("v") == std::vector<double>{1, 2, 3});
        r.endSection();
        CHECK(r.atEnd());
    }
    auto failure = [&](auto&& read) {
        StateReader r(b, 0, b.size(), "f.ckpt");
        auto e = errorOf([&] {
            r.beginSection("/root/a", "Thing");
            read(r);
        });
        REQUIRE(e);
        CHECK(e->kind() == ErrorKind::Input);
        return std::string(e->what());
    };
    SECTION("another name") {
        CHECK(failure([](StateReader& r) { r.getDouble("time"); }) ==
              "f.ckpt: error: [/root/a] expected record 'time', found 't': the checkpoint was written by another version "
              "of the component");
    }
    SECTION("another type") {
        CHECK(failure([](StateReader& r) { r.getLong("t"); }) ==
              "f.ckpt: error: [/root/a] record 't' holds float64 values, int64 expected");
    }
    SECTION("another size") {
        CHECK(failure([](StateReader& r) {
                  r.getDouble("t"), r.getLong("n"), r.getBool("on"), r.getText("label");
                  double x[4];
                  r.getInto("v", x, 4);
              }) == "f.ckpt: error: [/root/a] record 'v' has 3 values, this scene needs 4");
    }
    SECTION("a record left unread") {
        CHECK(failure([](StateReader& r) {
                  r.getDouble("t"), r.getLong("n"), r.getBool("on"), r.getText("label");
                  r.endSection();
              }) == "f.ckpt: error: [/root/a] record 'v' was saved but is not read by this build: the checkpoint was "
                    "written by another version of the component");
    }
    SECTION("a record read past the section") {
        CHECK(failure([](StateReader& r) {
                  r.getDouble("t"), r.getLong("n"), r.getBool("on"), r.getText("label"), r.getDoubles("v");
                  r.getDouble("extra");
              }) == "f.ckpt: error: [/root/a] record 'extra' runs past the end of its section (byte " +
                        std::to_string(b.size()) + ")");
    }
    SECTION("another component") {
        StateReader r(b, 0, b.size(), "f.ckpt");
        auto e = errorOf([&] { r.beginSection("/root/b", "Thing"); });
        REQUIRE(e);
        CHECK_THAT(std::string(e->what()), StartsWith("f.ckpt: error: the state at byte ") &&
                                               Contains("is of Thing '/root/a', but this scene has Thing '/root/b' there"));
    }
}

TEST_CASE("A counting writer counts the bytes the records take and writes none", "[StateWriter]") {
    StateWriter w, c(StateWriter::CountOnly{});
    for (StateWriter* x : {&w, &c}) {
        x->beginSection("/root/a", "Thing");
        x->put("t", 1.5);
        x->put("n", 7L);
        x->put("on", true);
        x->put("label", std::string("abc"));
        const double v[3] = {1, 2, 3};
        x->put("v", v, 3);
        x->put("none", v, 0);
        x->endSection();
        x->beginSection("/root/b", "Other");
        x->endSection();
    }
    CHECK(c.size() == w.bytes().size());
    CHECK(w.size() == w.bytes().size());
    CHECK(c.bytes().empty());
    c.clear();
    CHECK(c.size() == 0);
}

TEST_CASE("The hash of bytes changes with any one byte", "[StateWriter]") {
    std::string s(37, 'a');
    const auto h = hashBytes(s.data(), s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        std::string t = s;
        t[i] ^= 0x10;
        CAPTURE(i);
        CHECK(hashBytes(t.data(), t.size()) != h);
    }
    CHECK(hashBytes(s.data(), 36) != h);  // and with the length
}

TEST_CASE("A restored simulation goes on bitwise as the one that saved", "[Simulation]") {
    TempDir dir;
    const fs::path ck = dir.path() / "a.ckpt";
    auto straight = scene(body());
    straight->run(7);
    auto first = scene(body());
    first->run(3);
    first->save(ck.string());
    CHECK_FALSE(fs::exists(ck.string() + ".tmp"));  // renamed over the target
    first->run(2);
    first->save(ck.string());  // overwritten: the state after 5 steps
    auto second = scene(body());
    second->restore(ck.string());
    CHECK(second->stepCount() == 5);
    CHECK(second->time() == first->time());
    CHECK(second->dt() == 0.01);
    second->run(2);
    CHECK(second->stepCount() == 7);
    CHECK(second->time() == straight->time());
    CHECK(sameBits(second->state("state").x(), straight->state("state").x()));
    CHECK(sameBits(second->state("state").v(), straight->state("state").v()));
}

TEST_CASE("A restart with another dt continues with it from the checkpoint's time", "[Simulation]") {
    TempDir dir;
    const fs::path ck = dir.path() / "a.ckpt";
    auto first = scene(body());
    first->run(4);
    first->save(ck.string());
    std::string xml = body();
    xml.replace(xml.find("dt=\"0.01\""), 9, "dt=\"0.005\"");
    auto second = scene(xml);
    second->restore(ck.string());
    CHECK(second->time() == first->time());
    CHECK(second->dt() == 0.005);
    second->run(2);
    CHECK(second->time() == first->time() + 2 * 0.005);
}

TEST_CASE("A bad checkpoint file is an input error naming the file", "[Simulation]") {
    TempDir dir;
    const fs::path ck = dir.path() / "a.ckpt", bad = dir.path() / "bad.ckpt";
    const std::string good = checkpointAfter3(ck);
    const std::string name = bad.string();
    auto errorWith = [&](const std::string& bytes) {
        writeAll(bad, bytes);
        auto e = restoreError(body(), bad);
        REQUIRE(e);
        CHECK(e->kind() == ErrorKind::Input);
        return std::string(e->what());
    };
    SECTION("a flipped byte") {
        for (size_t at : {size_t(40), good.size() / 2, good.size() - 12}) {
            std::string b = good;
            b[at] ^= 0x04;
            CAPTURE(at);
            CHECK(errorWith(b) == name + ": error: checksum mismatch: the checkpoint is corrupt (changed or damaged since it "
                                         "was written)");
        }
    }
    SECTION("truncated") {
        CHECK(errorWith(good.substr(0, good.size() - 10)) ==
              name + ": error: truncated checkpoint: " + std::to_string(good.size() - 10) +
                  " bytes, its header announces " + std::to_string(good.size()));
        CHECK(errorWith(good.substr(0, 20)) == name + ": error: truncated checkpoint: 20 bytes, less than its header");
        CHECK(errorWith(good.substr(0, 5)) == name + ": error: truncated checkpoint: 5 bytes");
        CHECK(errorWith("") == name + ": error: truncated checkpoint: 0 bytes");
    }
    SECTION("bytes after the end") {
        CHECK(errorWith(good + "xyz") == name + ": error: the checkpoint has 3 bytes after its end");
    }
    SECTION("the wrong magic") {
        std::string b = good;
        b[0] = 'X';
        CHECK(errorWith(b) == name + ": error: not a Fascia checkpoint (it does not start with \"FASCIACK\")");
        CHECK(errorWith("<Node name=\"root\"/>\n") ==
              name + ": error: not a Fascia checkpoint (it does not start with \"FASCIACK\")");
    }
    SECTION("another format version") {
        std::string b = good;
        const std::uint32_t v = 2;
        std::memcpy(&b[8], &v, 4);
        CHECK(errorWith(b) == name + ": error: checkpoint format version 2; this build reads version 1");
    }
    SECTION("a missing file, a folder") {
        auto e = restoreError(body(), dir.path() / "none.ckpt");
        REQUIRE(e);
        CHECK(std::string(e->what()) ==
              (dir.path() / "none.ckpt").string() + ": error: cannot read the checkpoint: No such file or directory");
        e = restoreError(body(), dir.path());
        REQUIRE(e);
        CHECK(std::string(e->what()) == dir.path().string() +
                                            ": error: not a regular file: give the checkpoint file fascia-run wrote (--checkpoint)");
    }
    SECTION("another scene: a changed parameter, a component more or less") {
        auto e = restoreError(body("force=\"0 0 -1\"", "3"), ck);
        REQUIRE(e);
        CHECK(std::string(e->what()) ==
              ck.string() + ": error: the checkpoint was written by another scene: TestMass '/root/body/mass' differs (a "
                            "parameter, or the content of a file it reads)\n" +
                  ck.string() + ": note: restart with the scene (and the mesh files) that wrote it");
        std::string more = body();
        more.replace(more.find("  </Node>"), 0, "    <TestCounter name=\"extra\" label=\"x\"/>\n");
        e = restoreError(more, ck);
        REQUIRE(e);
        CHECK_THAT(std::string(e->what()), Contains("error: the checkpoint was written by another scene: this scene has "
                                                    "TestCounter '/root/body/extra', which the checkpoint does not"));
    }
    SECTION("restore after the run started") {
        auto sim = scene(body());
        sim->run(1);
        auto e = errorOf([&] { sim->restore(ck.string()); });
        REQUIRE(e);
        CHECK_THAT(std::string(e->what()), Contains("restore() on a simulation that has already started"));
    }
}

TEST_CASE("The dt of the root and its end time are not part of the scene hash, every other parameter is", "[Simulation]") {
    auto a = scene(body());
    std::string other = body();
    other.replace(other.find("dt=\"0.01\""), 9, "dt=\"0.02\" endTime=\"3\" dtSafety=\"0.3\"");
    CHECK(scene(other)->sceneHash() == a->sceneHash());
    CHECK(scene(body("force=\"0 0 -2\""))->sceneHash() != a->sceneHash());
    CHECK(scene(body("force=\"0 0 -1\" nanNode=\"1\""))->sceneHash() != a->sceneHash());
}

TEST_CASE("A NaN injected by a force field is caught in its step and the last good state is the step before", "[Simulation]") {
    TempDir dir;
    const fs::path ck = dir.path() / "good.ckpt";
    const long every = GENERATE(1L, 2L, 100L);  // a snapshot every step, or a replay from an older one
    CAPTURE(every);
    auto sim = scene(body("force=\"0 0 -1\" nanAtStep=\"6\" nanNode=\"2\""));
    sim->setSnapshotEvery(every);
    auto e = errorOf([&] { sim->run(10); });
    REQUIRE(e);
    CHECK(e->kind() == ErrorKind::Simulation);
    CHECK_THAT(e->message(), StartsWith("[/root/body/nan] step 6: non-finite force"));
    CHECK_THAT(e->message(), Contains("; at t = 0.06 s (the end of step 6)"));
    CHECK(sim->failedStep() == 6);
    CHECK(sim->saveLastGoodState(ck.string()) == 5);
    auto straight = scene(body("force=\"0 0 -1\" nanAtStep=\"6\" nanNode=\"2\""));
    straight->run(5);
    CHECK(sameBits(sim->state("state").x(), straight->state("state").x()));
    auto restored = scene(body("force=\"0 0 -1\" nanAtStep=\"6\" nanNode=\"2\""));
    restored->restore(ck.string());
    CHECK(restored->stepCount() == 5);
    CHECK(sameBits(restored->state("state").x(), straight->state("state").x()));
    CHECK(sameBits(restored->state("state").v(), straight->state("state").v()));
    // the restored run fails at the same step again (TestNaN's step counter was saved)
    auto again = errorOf([&] { restored->run(3); });
    REQUIRE(again);
    CHECK_THAT(again->message(), StartsWith("[/root/body/nan] step 6: "));
}

TEST_CASE("Without snapshots there is no last good state", "[Simulation]") {
    TempDir dir;
    auto sim = scene(body("force=\"0 0 -1\" nanAtStep=\"2\""));
    sim->setSnapshotEvery(0);
    CHECK(errorOf([&] { sim->run(3); }));
    CHECK(sim->failedStep() == 2);
    CHECK(sim->saveLastGoodState((dir.path() / "x.ckpt").string()) == -1);
    CHECK_FALSE(fs::exists(dir.path() / "x.ckpt"));
    auto ok = scene(body());
    ok->run(2);
    CHECK(ok->saveLastGoodState((dir.path() / "y.ckpt").string()) == -1);  // no failed step
}
