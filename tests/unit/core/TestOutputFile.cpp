/// core::OutputFile (fascia/base/CommandLine.h): a file written whole or not at all, and what it does
/// with the signals that may interrupt the write. Each signal case runs in a child process.
#include "fascia/base/CommandLine.h"

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace fs = std::filesystem;
using fascia::core::OutputFile;

namespace {

/// A fresh folder, removed at the end.
struct Folder {
    fs::path dir;
    Folder() {
        std::string t = (fs::temp_directory_path() / "fascia-output-file-XXXXXX").string();
        REQUIRE(::mkdtemp(t.data()));
        dir = t;
    }
    ~Folder() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

/// Runs body in a child process; its wait status.
int inChild(const std::function<void()>& body) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        body();
        std::_Exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
}

int caught = 0;
void countSignal(int) { ++caught; }

} // namespace

TEST_CASE("An output file appears only at commit, and not at all when it is not committed", "[OutputFile]") {
    Folder f;
    const std::string path = (f.dir / "out.txt").string();
    {
        OutputFile out(path);
        out.stream() << "half";
        CHECK(fs::exists(path + ".tmp"));
        CHECK_FALSE(fs::exists(path));
    }
    CHECK_FALSE(fs::exists(path + ".tmp"));
    CHECK_FALSE(fs::exists(path));
    {
        OutputFile out(path);
        out.stream() << "whole\n";
        out.commit();
    }
    CHECK(fs::exists(path));
    CHECK_FALSE(fs::exists(path + ".tmp"));
}

TEST_CASE("SIGTERM during the write removes the temporary file and ends the program as SIGTERM does", "[OutputFile]") {
    Folder f;
    const std::string path = (f.dir / "out.txt").string();
    const int status = inChild([&] {
        OutputFile out(path);
        out.stream() << "half" << std::flush;
        ::raise(SIGTERM);
        std::_Exit(7);  // not reached: the signal ends the child
    });
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == SIGTERM);
    CHECK_FALSE(fs::exists(path + ".tmp"));
    CHECK_FALSE(fs::exists(path));
}

TEST_CASE("A signal the program ignores stays ignored (nohup), and the program's handlers come back", "[OutputFile]") {
    Folder f;
    const std::string path = (f.dir / "out.txt").string();
    const int status = inChild([&] {
        std::signal(SIGHUP, SIG_IGN);
        std::signal(SIGINT, countSignal);
        {
            OutputFile out(path);
            out.stream() << "whole\n";
            ::raise(SIGHUP);  // ignored: the write goes on
            out.commit();
        }
        ::raise(SIGINT);  // the program's own handler again
        std::_Exit(caught == 1 ? 0 : 5);
    });
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    CHECK(fs::exists(path));
}

TEST_CASE("SIGINT during the write removes the file, then reaches the program's own handler", "[OutputFile]") {
    Folder f;
    const std::string path = (f.dir / "out.txt").string();
    const int status = inChild([&] {
        std::signal(SIGINT, countSignal);
        OutputFile out(path);
        out.stream() << "half" << std::flush;
        ::raise(SIGINT);
        std::_Exit(caught == 1 && !fs::exists(path + ".tmp") ? 0 : 5);
    });
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    CHECK_FALSE(fs::exists(path + ".tmp"));
}
