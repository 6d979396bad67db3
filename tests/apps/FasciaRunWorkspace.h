#pragma once
/// What the fascia-run tests share: a temporary folder holding one test's scenes and output, and a
/// way to run fascia-run (the FASCIA_RUN the test is compiled with), or another program, in it.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fasciaruntest {

namespace fs = std::filesystem;

/// The whole of a file (empty when it cannot be read).
inline std::string slurpFile(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// A temporary folder with the scenes and the output folders of one test, removed at the end.
class Workspace {
public:
    Workspace() {
        std::string tmpl = (fs::temp_directory_path() / "fascia-run-test-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
        m_dir = fs::canonical(tmpl);
    }
    ~Workspace() {
        std::error_code ec;
        fs::remove_all(m_dir, ec);
    }
    Workspace(const Workspace&) = delete;
    Workspace& operator=(const Workspace&) = delete;

    const fs::path& dir() const { return m_dir; }
    std::string write(const std::string& name, const std::string& text) const {
        const fs::path p = m_dir / name;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
        return p.string();
    }

    struct Result {
        int code = -1;
        std::string out, err;
        /// The summary line ("fascia-run: N steps, ..."), empty when there is none.
        std::string summary() const {
            std::istringstream in(out);
            for (std::string line; std::getline(in, line);)
                if (line.rfind("fascia-run: ", 0) == 0) return line;
            return {};
        }
        std::string firstErrLine() const { return err.substr(0, err.find('\n')); }
    };

    /// Runs fascia-run (or `program`) in dir() with args (shell words) and optional environment
    /// assignments; its output goes to hidden files of dir(); a run still going after 60 s is killed
    /// (exit code 124).
    Result run(const std::string& args, const std::string& env = "", const std::string& program = FASCIA_RUN) const {
        const std::string out = (m_dir / ".stdout").string(), err = (m_dir / ".stderr").string();
        const std::string cmd = "cd '" + m_dir.string() + "' && " + env + " timeout -s KILL 60 '" + program + "' " + args +
                                " >'" + out + "' 2>'" + err + "' </dev/null";
        const int status = std::system(cmd.c_str());
        Result r;
        r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.out = slurpFile(out);
        r.err = slurpFile(err);
        return r;
    }

    /// The names of the files under folder (relative to dir()), sorted.
    std::vector<std::string> filesIn(const std::string& folder) const {
        std::vector<std::string> out;
        std::error_code ec;
        for (auto& e : fs::recursive_directory_iterator(m_dir / folder, ec)) out.push_back(e.path().filename().string());
        std::sort(out.begin(), out.end());
        return out;
    }

private:
    fs::path m_dir;
};

} // namespace fasciaruntest
