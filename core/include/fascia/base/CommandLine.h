#pragma once
/// The command line of Fascia's programs (fascia-run, fascia-bench, fascia-dump,
/// fascia-param-coverage, fascia-haptics-demo): the arguments read one by one, with the same
/// messages everywhere for an unknown option, a missing value and a number out of its range; the
/// memory a count may fill; and output files written whole or not at all. Header only, so that a
/// program built out of tree against an installed Fascia (examples/haptics) has it too.
///
///   CommandLine cl("fascia-x", argc, argv);
///   while (cl.next()) {
///       if (cl.isHelp()) { std::cout << kHelp; return 0; }
///       else if (cl.is("--steps")) steps = cl.integer(0, 1000);
///       else if (cl.is("--output")) output = cl.path();
///       else if (cl.isOption()) cl.unknownOption();
///       else scene = cl.arg();
///   }
///
/// A bad command line prints "PROGRAM: message" and "(see PROGRAM --help)" on stderr and exits 1.
#include "fascia/base/Error.h"
#include "fascia/base/Format.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <signal.h>  // sigaction
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>

namespace fascia::core {

class CommandLine {
public:
    CommandLine(std::string program, int argc, char** argv) : m_program(std::move(program)), m_argc(argc), m_argv(argv) {}

    const std::string& program() const { return m_program; }
    /// Moves to the next argument; false after the last one.
    bool next() {
        if (m_i + 1 >= m_argc) return false;
        m_arg = m_argv[++m_i];
        return true;
    }
    /// The argument next() moved to.
    const std::string& arg() const { return m_arg; }
    bool is(const char* name) const { return m_arg == name; }
    bool isHelp() const { return m_arg == "--help" || m_arg == "-h"; }
    /// Anything that starts with '-' is an option, a known one or an error: never a file name.
    bool isOption() const { return !m_arg.empty() && m_arg[0] == '-'; }

    /// The value of the option just read (the next argument, consumed). None, an empty one or
    /// another option ("--...") is "OPTION needs WHAT".
    std::string text(const std::string& what = "a value") {
        const char* v = value();
        if (!v || !*v || (v[0] == '-' && v[1] == '-')) fail(m_arg + " needs " + what);
        return v;
    }
    /// A file or folder name: as text(), but nothing that starts with '-' is taken for one (write
    /// ./-name for such a file), so that a forgotten value never makes a file of the next option.
    std::string path(const std::string& what = "a value") {
        const char* v = value();
        if (!v || !*v || v[0] == '-') fail(m_arg + " needs " + what);
        return v;
    }
    /// An optional value: the next argument when it is not an option (consumed), else "".
    std::string optionalValue() { return m_i + 1 < m_argc && m_argv[m_i + 1][0] != '-' ? m_argv[++m_i] : std::string(); }
    /// A whole number in [lo, hi]; a value that is not one (1e3, 1x, 2.5), or out of the range,
    /// is "OPTION needs an integer in [lo, hi], not 'VALUE'".
    long integer(long lo, long hi) {
        const std::string v = text();
        char* end = nullptr;
        errno = 0;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (*end || errno == ERANGE || n < lo || n > hi)
            fail(m_arg + " needs an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], not '" + v + "'");
        return n;
    }
    /// A finite number > 0: "OPTION needs a positive number, not 'VALUE'" (fascia-run's --time, --dt).
    double positive() {
        const std::string v = text();
        const double d = parseReal(v);
        if (!(d > 0)) fail(m_arg + " needs a positive number, not '" + v + "'");
        return d;
    }
    /// A finite number in [lo, hi] (no upper bound when hi is infinite): "OPTION needs a number of at
    /// least LO, not 'VALUE'" or "OPTION needs a number in [LO, HI], not 'VALUE'".
    double number(double lo, double hi = HUGE_VAL) {
        const std::string v = text();
        const double d = parseReal(v);
        if (!(d >= lo && d <= hi))
            fail(m_arg + " needs a number " + (std::isinf(hi) ? "of at least " + realText(lo) : "in [" + realText(lo) + ", " + realText(hi) + "]") +
                 ", not '" + v + "'");
        return d;
    }

    /// A bad command line: "PROGRAM: message", then where to look, on stderr; exits 1.
    [[noreturn]] void fail(const std::string& message) const {
        std::cout.flush();
        std::cerr << m_program << ": " << message << "\n(see " << m_program << " --help)\n";
        std::exit(1);
    }
    [[noreturn]] void unknownOption() const { fail("unknown option '" + m_arg + "'"); }

    /// x with 6 significant digits ("%g"), as the messages write numbers.
    static std::string realText(double x) { return formatNumber(x, 6); }

private:
    const char* value() { return m_i + 1 < m_argc ? m_argv[++m_i] : nullptr; }
    /// v as a finite number, or NaN when it is not one whole (trailing text, inf, nan, overflow).
    static double parseReal(const std::string& v) {
        char* end = nullptr;
        const double d = std::strtod(v.c_str(), &end);
        return end == v.c_str() || *end || !std::isfinite(d) ? NAN : d;
    }

    std::string m_program, m_arg;
    int m_argc;
    char** m_argv;
    int m_i = 0;
};

/// The bytes a program may fill with what its command line asks for: half of the physical memory
/// (sysconf), or of the cgroup's limit when that is lower, the other half left to the system and to
/// other programs. A count whose estimate passes it is refused before anything is allocated: an
/// OOM kill or std::bad_alloc half-way through tells the user nothing.
inline double memoryBudgetBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    double bytes = pages > 0 && page > 0 ? double(pages) * double(page) : 4.0 * (1u << 30);  // unknown: 4 GiB
    for (const char* limit : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        double b = 0;
        if (std::ifstream(limit) >> b && b > 0 && b < bytes) bytes = b;  // ("max": no limit, not read)
    }
    return bytes / 2;
}

/// A byte count as a person reads it: "512 B", "23.4 GiB", "71.1 PiB".
inline std::string bytesText(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024 && u < 6) bytes /= 1024, ++u;
    char b[48];
    std::snprintf(b, sizeof b, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
    return b;
}

/// A count as a whole number ("526587083"), in %g beyond what a long holds exactly.
inline std::string countText(double n) {
    return n < 1e15 ? std::to_string(long(std::floor(n))) : CommandLine::realText(n);
}

/// Fails unless `count` items of about `bytesEach` bytes fit in memoryBudgetBytes(): "PROGRAM: WHAT
/// needs more memory than this machine has", then on a second line the estimate and the limit
/// (`limit`, or else the number of items that fit), which depend on the machine; exits 1.
inline void requireMemory(const std::string& program, const std::string& what, double count, double bytesEach,
                          const std::string& items, const std::string& limit = "") {
    const double budget = memoryBudgetBytes();
    if (count * bytesEach <= budget) return;
    std::cout.flush();
    std::cerr << program << ": " << what << " needs more memory than this machine has\n(" << CommandLine::realText(count) << " "
              << items << " of about " << CommandLine::realText(bytesEach) << " bytes need " << bytesText(count * bytesEach)
              << "; a program may fill " << bytesText(budget) << " here, half of the memory: "
              << (limit.empty() ? "at most " + countText(budget / bytesEach) + " " + items : limit) << ")\n";
    std::exit(1);
}

/// Fails (an output error located at path: exit code 1) unless path can be written as a regular
/// file: not a folder, a FIFO or a device, in an existing folder this process may write into.
/// Checked before the work starts, so that a bad path costs nothing and writes nothing.
inline void requireOutputFile(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) throwOutputError({path, 0}, "output file '" + path + "' is a folder, not a file");
        if (!S_ISREG(st.st_mode)) throwOutputError({path, 0}, "output file '" + path + "' is not a regular file");
    }
    const std::string::size_type slash = path.rfind('/');
    const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
        throwOutputError({path, 0}, "cannot write '" + path + "' into the folder '" + dir + "': " + std::strerror(errno));
}

/// A file written whole or not at all: the text goes to PATH.tmp, beside PATH so that the rename
/// stays in one file system (as Simulation::save writes checkpoints, core/src/SimulationState.cpp),
/// and commit() renames it over PATH. Destroyed without commit() (an error, an exception), or
/// interrupted by SIGINT, SIGTERM or SIGHUP, it removes PATH.tmp. One at a time in a program: while
/// it lives it handles those signals (not one the program ignores, as under nohup), then hands each
/// to the handler it had before; afterwards the program's handlers are as they were.
class OutputFile {
public:
    explicit OutputFile(std::string path) : m_path(std::move(path)), m_tmp(m_path + ".tmp") {
        requireOutputFile(m_path);
        if (m_tmp.size() >= kMaxPath) throwOutputError({m_path, 0}, "output file '" + m_path + "': the path is too long");
        if (tmpForSignals()[0]) throw std::logic_error("fascia::core::OutputFile: a second one while '" + std::string(tmpForSignals()) +
                                                       "' is open (one at a time)");
        std::strcpy(tmpForSignals(), m_tmp.c_str());
        arm();
        m_out.open(m_tmp, std::ios::binary | std::ios::trunc);
        if (!m_out) {
            const int err = errno;
            forget();
            throwOutputError({m_path, 0}, "cannot write '" + m_tmp + "': " + std::strerror(err));
        }
    }
    ~OutputFile() {
        if (m_committed) return;
        m_out.close();
        ::unlink(m_tmp.c_str());
        forget();
    }
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    std::ostream& stream() { return m_out; }
    /// False once a write failed (a full disk): the caller may stop early; commit() then throws.
    bool good() const { return bool(m_out); }
    /// Closes PATH.tmp and renames it over PATH; an output error (PATH.tmp removed) when a write failed.
    void commit() {
        errno = 0;  // (what a failed close or rename sets, not an older call's)
        m_out.close();
        const bool written = bool(m_out);
        if (!written || ::rename(m_tmp.c_str(), m_path.c_str()) != 0) {
            const int err = errno;
            ::unlink(m_tmp.c_str());
            forget();
            m_committed = true;
            throwOutputError({m_path, 0}, "cannot write '" + m_path + "': " +
                                              (err ? std::strerror(err) : written ? "the rename failed" : "a write failed"));
        }
        forget();
        m_committed = true;
    }

private:
    static constexpr size_t kMaxPath = 4096;
    /// The temporary file a signal removes (a fixed buffer: a handler may not allocate).
    static char* tmpForSignals() {
        static char path[kMaxPath];
        return path;
    }
    static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
    /// The actions the program had for kSignals before arm() (restored by forget() and by a signal).
    static struct sigaction* previous() {
        static struct sigaction old[3];
        return old;
    }
    static void arm() {
        struct sigaction mine {};
        mine.sa_handler = onSignal;
        sigemptyset(&mine.sa_mask);
        for (int i = 0; i < 3; ++i) {
            ::sigaction(kSignals[i], nullptr, &previous()[i]);
            if (previous()[i].sa_handler != SIG_IGN) ::sigaction(kSignals[i], &mine, nullptr);
        }
    }
    /// (only async-signal-safe calls: unlink, sigaction, raise)
    static void onSignal(int s) {
        ::unlink(tmpForSignals());
        for (int i = 0; i < 3; ++i)
            if (kSignals[i] == s) ::sigaction(s, &previous()[i], nullptr);
        std::raise(s);
    }
    static void forget() {
        for (int i = 0; i < 3; ++i)
            if (previous()[i].sa_handler != SIG_IGN) ::sigaction(kSignals[i], &previous()[i], nullptr);
        tmpForSignals()[0] = '\0';
    }

    std::string m_path, m_tmp;
    std::ofstream m_out;
    bool m_committed = false;
};

} // namespace fascia::core
