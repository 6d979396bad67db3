#pragma once
/// TestCounter: an observer with a parameter of every type, counting the calls it gets.
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

#include <limits>

namespace fascia::test {

/// Order in which TestCounters were initialised in this process (for init-order tests).
int nextInitIndex();

class TestCounter : public core::BaseObserver {
public:
    // one parameter of each type
    core::Param<double> m_scale{this, core::ParamSpec("scale").unit("m").min(0).max(10, true).help("a length in [0, 10)"), 1.0};
    core::Param<double> m_rate{this, core::ParamSpec("rate").unit("1/s").above(0).help("a rate > 0"), 2.0};
    core::Param<double> m_ceiling{this, core::ParamSpec("ceiling").below(5).help("a number < 5"), 0.0};
    core::Param<int> m_iterations{this, core::ParamSpec("iterations").min(1).max(100).help("an int in [1, 100]"), 10};
    core::Param<bool> m_enabled{this, core::ParamSpec("enabled").help("a switch"), true};
    core::Param<std::string> m_mode{this, core::ParamSpec("mode").choices({"fast", "accurate", "debug"}).help("an enum"), "fast"};
    core::Param<std::string> m_comment{this, core::ParamSpec("comment").help("free text")};
    core::Param<Vec3> m_direction{this, core::ParamSpec("direction").min(-1).max(1).help("a vector, entries in [-1, 1]"), Vec3(0, 0, 1)};
    core::Param<IndexList> m_indices{this, core::ParamSpec("indices").max(1000).help("node indices <= 1000")};
    core::Param<NumberList> m_box{this, core::ParamSpec("box").count(6).unit("m").help("xmin ymin zmin xmax ymax zmax")};
    core::Param<NumberList> m_values{this, core::ParamSpec("values").help("numbers, literal or linked (\"@other.values\")")};
    core::Param<FilePath> m_file{this, core::ParamSpec("file").help("a file, relative to the scene")};
    core::Param<std::string> m_label{this, core::ParamSpec("label").required().help("a required label")};
    core::Link<TestCounter> m_partner{this, core::ParamSpec("partner").help("another TestCounter")};

    // outputs
    core::Param<int> m_beginSteps{this, core::ParamSpec("beginSteps").output().help("beginStep calls"), 0};
    core::Param<int> m_observed{this, core::ParamSpec("observed").output().help("observe calls"), 0};
    core::Param<int> m_initIndex{this, core::ParamSpec("initIndex").output().help("order of init in the process"), -1};
    core::Param<double> m_valuesSum{this, core::ParamSpec("valuesSum").output().help("sum of values at init"), 0.0};
    core::Param<double> m_dtSeen{this, core::ParamSpec("dtSeen").unit("s").output().help("last dtChanged"), 0.0};
    core::Param<double> m_lastTime{this, core::ParamSpec("lastTime").unit("s").output().help("t of the last beginStep"), -1.0};
    core::Param<int> m_partnerInitIndex{this, core::ParamSpec("partnerInitIndex").output().help("partner's initIndex seen at init"), -2};
    core::Param<int> m_stateSizeAtInit{this, core::ParamSpec("stateSizeAtInit").output().help("size of the state in context at init (-1: none)"), -2};

    void init() override {
        double s = 0;
        for (double v : m_values.get()) s += v;
        m_valuesSum.set(s);
        if (m_partner) m_partnerInitIndex.set(m_partner->m_initIndex.get());
        auto* state = node()->findInContext<core::BaseMechanicalState>();
        m_stateSizeAtInit.set(state ? int(state->size()) : -1);
        if (m_mode.get() == "debug" && m_comment.get() == "fail") fail(m_comment, "asked to fail");
        m_initIndex.set(nextInitIndex());
    }
    void dtChanged(double dt) override { m_dtSeen.set(dt); }
    void beginStep(double t, double dt) override {
        m_beginSteps.set(m_beginSteps.get() + 1);
        m_lastTime.set(t);
    }
    void observe(double t, long step) override { m_observed.set(m_observed.get() + 1); }
};

} // namespace fascia::test
