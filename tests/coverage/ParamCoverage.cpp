// fascia-param-coverage: checks that the tests exercised every registered component parameter.
//
//   fascia-param-coverage --list
//   fascia-param-coverage --log LOG --allow ALLOWLIST [--tests NAMES]
//
// --list prints every parameter of every component registered by the built-in plugins (the list
// `fascia-run --describe` prints), one "Component.parameter" a line. With --log it reads the log
// that the core writes while FASCIA_PARAM_LOG is set (fascia/base/ParamLog.h) and fails, listing
// them, when parameters are neither exercised nor in the allow-list. An input parameter is
// exercised when a test sets it (scene attribute, link or code); an output parameter (computed by
// the component itself) when a test or a scene link asks for it by name. --tests names the ctest
// entries of a full run: when some did not run (ctest -R ...), the check is skipped, saying so.
// See tests/coverage/README.md.
#include "fascia/base/CommandLine.h"
#include "fascia/base/InputFile.h"
#include "fascia/plugin/PluginManager.h"
#include "fascia/plugin/Registry.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

using namespace fascia::core;

namespace {

struct Declared {
    std::string component, type, param;
    bool output = false;
    std::string key() const { return component + "." + param; }
};

/// Every parameter of every registered component, in registry order.
std::vector<Declared> registeredParams() {
    PluginManager::instance().loadDefaultPlugins();
    std::vector<Declared> out;
    for (auto& [name, entry] : Registry::instance().entries()) {
        auto c = Registry::instance().create(name);
        const std::string type = demangledTypeName(typeid(*c).name());
        for (BaseParam* p : c->params()) out.push_back({name, type, p->name(), p->spec().isOutput});
    }
    return out;
}

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> f;
    std::istringstream in(line);
    for (std::string s; std::getline(in, s, sep);) f.push_back(s);
    return f;
}

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return {};
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

/// What the log says: kind -> "className|type|param" seen, and the test entries that ran.
struct Log {
    std::set<std::string> set, lookup, ran;
    bool covers(const std::set<std::string>& seen, const Declared& d) const {
        for (auto& s : seen) {
            const auto f = split(s, '\t');
            if (f.size() == 3 && f[2] == d.param && (f[0] == d.component || (f[0].empty() && f[1] == d.type)))
                return true;
        }
        return false;
    }
};

Log readLog(const std::string& path) {
    Log log;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        const auto tab = line.find('\t');
        if (tab == std::string::npos) continue;
        const std::string kind = line.substr(0, tab), rest = line.substr(tab + 1);
        if (kind == "set") log.set.insert(rest);
        else if (kind == "lookup") log.lookup.insert(rest);
        else if (kind == "ran") log.ran.insert(rest);
    }
    return log;
}

/// The allow-list: "Component.parameter  reason" lines in two sections.
struct AllowList {
    std::map<std::string, std::string> untestable, notYet;  // key -> reason
    std::vector<std::string> problems;
};

AllowList readAllowList(const std::string& path) {
    AllowList a;
    std::ifstream in(path);
    if (!in) a.problems.push_back(path + ": cannot read the allow-list");
    std::map<std::string, std::string>* section = nullptr;
    int lineNo = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        const std::string t = trim(line);
        if (t.empty() || t[0] == '#') continue;
        const std::string where = path + ":" + std::to_string(lineNo) + ": ";
        if (t == "[cannot be tested]") section = &a.untestable;
        else if (t == "[not yet covered (to be tested)]") section = &a.notYet;
        else if (t[0] == '[') a.problems.push_back(where + "unknown section " + t);
        else if (!section) a.problems.push_back(where + "an entry before the first section");
        else {
            const auto sp = t.find_first_of(" \t");
            const std::string key = t.substr(0, sp);
            const std::string reason = sp == std::string::npos ? std::string() : trim(t.substr(sp));
            if (section == &a.untestable && reason.empty())
                a.problems.push_back(where + key + " is allowed without a reason");
            if (!section->emplace(key, reason).second) a.problems.push_back(where + key + " is listed twice");
        }
    }
    return a;
}

/// The ctest entries that a full run has, one a line; those that did not log "ran".
std::vector<std::string> notRun(const std::string& namesFile, const Log& log) {
    std::vector<std::string> out;
    std::ifstream in(namesFile);
    for (std::string name; std::getline(in, name);)
        if (!name.empty() && !log.ran.count(name)) out.push_back(name);
    return out;
}

int check(const std::string& logPath, const std::string& allowPath, const std::string& testsFile) {
    const Log log = readLog(logPath);
    if (!testsFile.empty()) {
        const auto missing = notRun(testsFile, log);
        if (!missing.empty()) {
            std::cout << "param-coverage: skipped: a partial run (" << missing.size()
                      << " test entries did not run, e.g. '" << missing.front()
                      << "'); run the whole ctest to check the parameter coverage\n";
            return 0;
        }
    }
    const AllowList allow = readAllowList(allowPath);
    std::vector<std::string> uncovered, wrongAllow, nowCovered, problems = allow.problems;
    std::set<std::string> declared;
    size_t covered = 0;
    for (const Declared& d : registeredParams()) {
        declared.insert(d.key());
        const bool ok = d.output ? log.covers(log.lookup, d) : log.covers(log.set, d);
        covered += ok;
        if (ok && allow.untestable.count(d.key())) wrongAllow.push_back(d.key());
        if (ok && allow.notYet.count(d.key())) nowCovered.push_back(d.key());
        if (!ok && !allow.untestable.count(d.key()) && !allow.notYet.count(d.key()))
            uncovered.push_back(d.key() + (d.output ? " (output: nothing links to it or asks for it)" : " (never set)"));
    }
    for (auto* m : {&allow.untestable, &allow.notYet})
        for (auto& [key, reason] : *m)
            if (!declared.count(key)) problems.push_back(allowPath + ": " + key + " is no registered parameter");
    std::cout << "param-coverage: " << covered << " of " << declared.size() << " registered parameters exercised, "
              << allow.untestable.size() << " allowed as not testable, " << allow.notYet.size()
              << " listed as not yet covered\n";
    for (auto& k : nowCovered)
        std::cout << "param-coverage: note: " << k << " is now exercised: remove it from the 'not yet covered' list\n";
    for (auto& k : allow.notYet)
        if (!std::count(nowCovered.begin(), nowCovered.end(), k.first))
            std::cout << "param-coverage: not yet covered (allow-listed, to be tested): " << k.first << "\n";
    for (auto& k : wrongAllow)
        problems.push_back(k + " is exercised by a test but allowed as not testable: remove it from the allow-list");
    for (auto& k : uncovered) problems.push_back("not exercised by any test: " + k);
    for (auto& p : problems) std::cout << "param-coverage: error: " << p << "\n";
    if (!problems.empty())
        std::cout << "param-coverage: FAILED: " << uncovered.size() << " parameters not exercised; test them, or add "
                  << "them to " << allowPath << " with the reason they cannot be\n";
    return problems.empty() ? 0 : 1;
}

const char* kHelp = R"(fascia-param-coverage: did the tests exercise every registered component parameter?

usage:
  fascia-param-coverage --list
  fascia-param-coverage --log LOG --allow ALLOWLIST [--tests NAMES]
  fascia-param-coverage --help

  --list           print every parameter of every registered component ("Component.parameter",
                   "output" after those the component computes)
  --log LOG        the parameter log of a test run (FASCIA_PARAM_LOG, fascia/base/ParamLog.h)
  --allow FILE     the allow-list (tests/coverage/ParamAllowList.txt)
  --tests NAMES    the ctest entries of a full run, one a line: when some did not run, the check is
                   skipped, saying so

exit codes: 0 every parameter exercised or allowed (or a skipped partial run); 1 a bad command line
or parameters not exercised; 2 a file that cannot be read (missing, a folder)
)";

} // namespace

int main(int argc, char** argv) {
    std::string logPath, allowPath, testsFile;
    bool list = false;
    CommandLine cl("fascia-param-coverage", argc, argv);
    while (cl.next()) {
        if (cl.isHelp()) {
            std::cout << kHelp;
            return 0;
        } else if (cl.is("--list")) list = true;
        else if (cl.is("--log")) logPath = cl.path();
        else if (cl.is("--allow")) allowPath = cl.path();
        else if (cl.is("--tests")) testsFile = cl.path();
        else if (cl.isOption()) cl.unknownOption();
        else cl.fail("unexpected argument '" + cl.arg() + "'");
    }
    if (!list && (logPath.empty() || allowPath.empty())) cl.fail("give --list, or --log LOG --allow ALLOWLIST [--tests NAMES]");
    try {
        if (list) {
            for (const Declared& d : registeredParams()) std::cout << d.key() << (d.output ? " output" : "") << "\n";
            return 0;
        }
        // (read whole, line by line: each at most half the memory)
        const auto limit = std::uintmax_t(memoryBudgetBytes() / 2);
        requireRegularFile(logPath, "parameter log", limit, {logPath, 0});
        requireRegularFile(allowPath, "list of allowed parameters", limit, {allowPath, 0});
        if (!testsFile.empty()) requireRegularFile(testsFile, "list of tests", limit, {testsFile, 0});
        return check(logPath, allowPath, testsFile);
    } catch (const Error& e) {
        std::cerr << e.what() << "\n";
        return e.kind() == ErrorKind::Input ? 2 : 1;
    } catch (const std::exception& e) {
        std::cerr << "fascia-param-coverage: " << e.what() << "\n";
        return 1;
    }
}
