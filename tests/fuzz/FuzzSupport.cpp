#include "FuzzSupport.h"

#include "fascia/base/Error.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>

namespace fascia::fuzz {

namespace fs = std::filesystem;

namespace {

/// The scratch folder, removed when the process exits normally.
struct Scratch {
    std::string dir;
    Scratch() {
        std::string tmpl = (fs::temp_directory_path() / "fascia-fuzz-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) {
            std::perror("fascia fuzz: cannot make a scratch folder");
            std::abort();
        }
        dir = tmpl;
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

[[noreturn]] void finding(const char* target, const std::string& what) {
    std::fprintf(stderr, "fascia fuzz %s: FINDING: %s\n", target, what.c_str());
    std::fflush(stderr);
    std::abort();
}

} // namespace

const std::string& scratchDir() {
    static Scratch scratch;
    return scratch.dir;
}

std::string writeScratch(const std::string& name, const uint8_t* data, size_t size) {
    const std::string path = scratchDir() + "/" + name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) {
        std::fprintf(stderr, "fascia fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
    return path;
}

std::string writeScratch(const std::string& name, const std::string& bytes) {
    return writeScratch(name, reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

void removeScratch(const std::string& name) {
    std::error_code ec;
    fs::remove(scratchDir() + "/" + name, ec);
}

void runExpectingLocatedErrors(const char* target, const std::function<void()>& f) {
    try {
        f();
        if (std::getenv("FASCIA_FUZZ_VERBOSE")) std::fprintf(stderr, "  accepted\n");
    } catch (const core::Error& e) {
        const bool expectedKind = e.kind() == core::ErrorKind::Input || e.kind() == core::ErrorKind::Output;
        if (!expectedKind) finding(target, std::string("fascia error of an unexpected kind: ") + e.what());
        if (e.loc().file.empty()) finding(target, std::string("fascia error without a location: ") + e.what());
        if (std::getenv("FASCIA_FUZZ_VERBOSE")) std::fprintf(stderr, "  %s\n", e.what());
        return;
    } catch (const std::exception& e) {
        finding(target, std::string("exception escaped: ") + e.what());
    } catch (...) {
        finding(target, "unknown exception escaped");
    }
}

} // namespace fascia::fuzz
