// The main() of every Catch2 test executable (cmake/FasciaTesting.cmake). Besides Catch2's own
// main, a listener appends "ran<TAB><test case name>" to the parameter-coverage log for each test
// case that starts, so that the coverage check (tests/coverage/README.md) can tell a complete run
// of the suite from a partial one. Without FASCIA_PARAM_LOG it does nothing.
#define CATCH_CONFIG_MAIN
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
