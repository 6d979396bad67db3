// The table of the device step's arrays (FASCIA_STEP_ARRAYS, fascia/cuda/StepLayout.h) against
// what the emulation uploads and wires (EmulatedRunner.h, the same loop over the table as
// CudaRunner.cu's upload): every row's array of the length the table gives and its pointer in
// StepArrays (null where it has no values), in scenes that give every row values; and a layout
// with one row left out of the upload, one pointer not wired, one array a value short, or one
// array of the setup a value short, each found by the same check (checkLayout, StepSetup.h) and
// named, row by row.
#include "EmulatedRunner.h"
#include "GroupCases.h"
#include "HEMLCases.h"
#include "LoadCases.h"

using namespace cudatest;

namespace {

/// A scene of the cantilever and the body elements beside its force field.
struct LayoutCase {
    std::string name;
    BodyParts parts;
    std::string body;
};

/// Scenes that give every row of the table values, in one order of the corner forces or the other:
/// TLED's tetrahedra and hexahedra with faces under pressure of both kinds, a lift (targets), a
/// Prony series and curved loads; HEML with a law of two fibres; HEML's springs; fibre arrays on
/// both kinds of element.
std::vector<LayoutCase> layoutCases() {
    const std::string loaded = loads::kPressures + kLift + prony() + loads::kCurvedForces;
    const std::string hexGrid =
        "<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"hexahedra\"/>";
    return {
        {"TLED on tetrahedra, loaded", {heml::kGrid, deviceLaw("TransverselyIsotropic").element, ""}, loaded},
        {"TLED on the mixed mesh, loaded", {hexGrid, deviceLaw("Orthotropic").element, mixedElements()}, loaded},
        {"HEML with two fibres and pressures", heml::parts(deviceLaw("Orthotropic")), loads::kPressures},
        {"HEML's springs", heml::springParts(), ""},
        {"groups with fibre arrays", groups::groupParts(groups::groupCase("three groups with fibre arrays"), Mesh::Mixed), ""},
    };
}

/// The emulation's upload (emulatedUpload) with row `skip` of the table left out.
template <class T>
cuda::StepArraysHost<T> uploadSkipping(const cuda::StepArraysHost<T>& h, int skip) {
    cuda::StepArraysHost<T> dev;
    static_cast<cuda::StepCounts&>(dev) = h;
    cuda::forEachStepArray<T>(
        [&](const cuda::StepArrayInfo& a, auto, auto, const auto& from, auto& to) {
            if (a.index != skip) to = from;
        },
        h, dev);
    return dev;
}

/// errors names the row `name` alone, once, where `found` (a fault in a row with values); none otherwise.
void namesOnly(const std::string& name, bool found, const std::vector<std::string>& errors) {
    CAPTURE(errors);
    if (!found) {
        CHECK(errors.empty());
        return;
    }
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].rfind(name + ":", 0) == 0);
}

/// The checks of one setup in T; has[k]: row k had values.
template <class T>
void checkSetup(const cuda::StepSetup& s, std::vector<bool>& has) {
    cuda::EmulatedRunner<T> runner(s);  // (its construction checks its arrays too: requireLayout)
    CHECK(runner.layoutErrors(s).empty());
    cuda::StepArraysHost<T> h = cuda::toArrays<T>(s), good = cuda::emulatedUpload(h);  // (view() gives mutable pointers)
    CHECK(cuda::checkLayout(s, h.view(), h).empty());
    cuda::StepArraysHost<T> dev = good;
    cuda::forEachStepArray<T>(
        [&](const cuda::StepArrayInfo& a, auto at, auto setup, const auto& array, auto& mine) {
            const bool values = !array.empty();
            has[size_t(a.index)] = has[size_t(a.index)] || values;
            CAPTURE(a.name, array.size());
            // left out of the upload
            dev = uploadSkipping(h, a.index);
            namesOnly(a.name, values, cuda::checkLayout(s, dev.view(), dev));
            // uploaded, not wired
            dev = good;
            cuda::StepArrays<T> d = dev.view();
            d.*at = nullptr;
            namesOnly(a.name, values, cuda::checkLayout(s, d, dev));
            // wired past its start
            if (values) {
                d.*at = mine.data() + 1;
                namesOnly(a.name, true, cuda::checkLayout(s, d, dev));
            }
            // a value short on the device
            if (values) {
                mine.pop_back();
                namesOnly(a.name, true, cuda::checkLayout(s, dev.view(), dev));
                dev = good;
            }
            // a value short in the setup (what toArrays copies)
            if constexpr (std::is_member_object_pointer_v<decltype(setup)>) {
                if (!(s.*setup).empty()) {
                    cuda::StepSetup t = s;
                    (t.*setup).pop_back();
                    cuda::StepArraysHost<T> th = cuda::emulatedUpload(cuda::toArrays<T>(t));
                    namesOnly(a.name, true, cuda::checkLayout(t, th.view(), th));
                }
            }
        },
        good, dev);
    // counts that are not the setup's
    cuda::StepArrays<T> d = dev.view();
    ++d.nNodes;
    CHECK(cuda::checkLayout(s, d, dev).size() == 1);
}

} // namespace

TEST_CASE("The emulation uploads and wires every array of the device step's table, and the check finds one left out", "[CudaStep]") {
    std::vector<bool> has(size_t(cuda::kStepArrayRows), false);
    for (const LayoutCase& c : layoutCases())
        for (const bool nodeOrder : {false, true}) {
            CAPTURE(c.name, nodeOrder);
            ForceProbe p = probeForces(scene(c.parts, "", c.body), 1.0);
            p.setup.forcesInNodeOrder = nodeOrder;
            checkSetup<double>(p.setup, has);
            checkSetup<float>(p.setup, has);
        }
    // every row had values in some scene: its being left out was found
    std::vector<std::string> names;
    cuda::forEachStepArray<double>([&](const cuda::StepArrayInfo& a, auto, auto) { names.push_back(a.name); });
    REQUIRE(names.size() == has.size());
    for (size_t k = 0; k < names.size(); ++k) {
        CAPTURE(names[k]);
        CHECK(has[k]);
    }
}

TEST_CASE("A layout whose arrays do not match the table is an internal error naming them", "[CudaStep]") {
    ForceProbe p = probeForces(scene(deviceLaw("NeoHookean"), ""), 1.0);
    cuda::StepArraysHost<double> h = uploadSkipping(cuda::toArrays<double>(p.setup), 0);
    try {
        cuda::requireLayout(cuda::checkLayout(p.setup, h.view(), h));
        FAIL("no error");
    } catch (const core::Error& e) {
        CHECK(e.kind() == core::ErrorKind::Internal);
        CHECK(std::string(e.what()).find("tet: 0 values on the device, 288 expected") != std::string::npos);
    }
    CHECK_NOTHROW(cuda::requireLayout({}));
}
