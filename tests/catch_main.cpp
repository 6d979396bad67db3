// The main() of every Catch2 test executable (cmake/FasciaTesting.cmake).
// - Each test case, and each leaf section, must run at least one assertion: Catch2's
//   NoAssertions warning is always on (a case that checks nothing fails), also when an
//   executable is run by hand. ctest adds -w NoTests (a filter that matches no case fails);
//   Catch2 v2 takes one -w on a command line, hence this one here.
// - A listener appends "ran<TAB><test case name>" to the parameter-coverage log for each test
//   case that starts, so that the coverage check (tests/coverage/README.md) can tell a complete
//   run of the suite from a partial one. Without FASCIA_PARAM_LOG it does nothing.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "fascia/base/ParamLog.h"

namespace {

struct RanListener : Catch::TestEventListenerBase {
    using TestEventListenerBase::TestEventListenerBase;
    void testCaseStarting(const Catch::TestCaseInfo& info) override {
        fascia::core::paramLogWrite("ran\t" + info.name);
    }
};

} // namespace

CATCH_REGISTER_LISTENER(RanListener)

int main(int argc, char* argv[]) {
    Catch::Session session;
    session.configData().warnings = Catch::WarnAbout::NoAssertions;
    const int rc = session.applyCommandLine(argc, argv);
    if (rc != 0) return rc;
    return session.run();
}
