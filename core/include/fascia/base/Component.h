#pragma once
/// Components: the building blocks of a scene. Each declares its parameters once (Param<T> members)
/// and goes through parse -> init (dependencies first) -> steps -> cleanup.
#include "fascia/base/Param.h"

#include <chrono>
#include <string>
#include <vector>

namespace fascia::core {

class Node;
class Component;
class StateWriter;
class StateReader;

/// Anything that holds parameters: components and nodes.
class Base {
public:
    Base();
    virtual ~Base() = default;
    Base(const Base&) = delete;
    Base& operator=(const Base&) = delete;

    const std::vector<BaseParam*>& params() const { return m_params; }
    BaseParam* findParam(const std::string& name) const;
    std::vector<std::string> paramNames() const;

    const std::string& name() const { return m_name.get(); }
    void setName(const std::string& n) { m_name.set(n); }
    /// Where it was declared in the scene (file:line), empty when built in code.
    const SourceLoc& loc() const { return m_loc; }
    void setLoc(SourceLoc l) { m_loc = std::move(l); }

    /// Type name as registered (the XML tag): "HEMLForceField", "Node".
    const std::string& className() const { return m_className; }
    void setClassName(std::string c) { m_className = std::move(c); }

    /// "/root/liver/liverFF"
    virtual std::string path() const = 0;

    /// A located input error about this object: "file:line: error: Type 'name': message".
    [[noreturn]] void fail(const std::string& message, std::vector<std::string> notes = {}) const;
    /// Same, located at a parameter's attribute.
    [[noreturn]] void fail(const BaseParam& p, const std::string& message, std::vector<std::string> notes = {}) const;
    /// An output of this object that cannot be written (ErrorKind::Output: fascia-run exits 1), located
    /// at p's attribute when given and set, else at the object.
    [[noreturn]] void failOutput(const BaseParam* p, const std::string& message, std::vector<std::string> notes = {}) const;
    /// A warning printed on stderr in compiler format.
    void warn(const std::string& message) const;

private:
    friend class BaseParam;
    std::vector<BaseParam*> m_params;
    SourceLoc m_loc;
    std::string m_className;

protected:
    Param<std::string> m_name{this, ParamSpec("name").help("name of this object, unique among its siblings")};
};

/// Accumulated wall time of one component's work.
struct Timer {
    double seconds = 0.0;
    long calls = 0;
};

/// Per-component timing is off by default (two clock reads per call, which add up over many small
/// components; docs/performance.md, lesson 14); fascia-run --timers and Simulation users turn it on.
void setTimersEnabled(bool on);
bool timersEnabled();

/// The clock the timers read, in seconds: std::chrono::steady_clock unless a test injects its
/// own with setTimerClock (nullptr restores steady_clock), so that timer tests need no wall clock.
using TimerClock = double (*)();
void setTimerClock(TimerClock clock);
double timerNow();

/// RAII: adds the elapsed time to a Timer (when timers are enabled) and counts the call.
class ScopedTimer {
public:
    explicit ScopedTimer(Timer& t) : m_t(t), m_on(timersEnabled()) {
        if (m_on) m_start = timerNow();
    }
    ~ScopedTimer() {
        if (m_on) m_t.seconds += timerNow() - m_start;
        ++m_t.calls;
    }
private:
    Timer& m_t;
    bool m_on;
    double m_start = 0.0;
};

class Component : public Base {
public:
    Component() = default;
    ~Component() override = default;

    Node* node() const { return m_node; }
    std::string path() const override;

    /// Called once, after every parameter is parsed and every link it holds is resolved and
    /// initialised (dependencies first). Precompute here; throw located errors via fail().
    virtual void init() {}
    /// Called when the time step changes (e.g. Prony coefficients depend on dt).
    virtual void dtChanged(double dt) {}
    /// Called once at the end of a run (flush files).
    virtual void cleanup() {}
    /// Called at the start of each step, before any force is computed.
    virtual void beginStep(double t, double dt) {}

    /// Writes what it carries from one step to the next (fascia/base/StateIO.h), between steps, for
    /// a checkpoint (Simulation::save) or the divergence check's snapshot: everything a step or an
    /// observation changes and the next one reads, so that a restored run continues bitwise as the
    /// straight one. Default: nothing (a component whose members are set at init only).
    virtual void saveState(StateWriter& out) const {}
    /// Reads back, in the same order, what saveState wrote; called after init() and the dtChanged()
    /// of the run's dt, before any step. Writes no file (observers continue their files at their next
    /// record); a record of the wrong name or size is an error of the reader.
    virtual void restoreState(StateReader& in) {}

    /// Components this one needs initialised first (besides those it links to by parameter).
    /// By default: the mesh source (BaseTopology) and the mechanical state found in its context,
    /// which most components read at init.
    virtual std::vector<Component*> dependencies() const;

    Timer& timer() { return m_timer; }
    const Timer& timer() const { return m_timer; }
    bool initialised() const { return m_initialised; }

private:
    friend class Node;
    friend class SceneInit;
    Node* m_node = nullptr;
    Timer m_timer;
    bool m_initialised = false;
};

/// A parameter naming another component by path ("@../loader", "@mo", "@/root/organ/mo").
/// Empty: the owner looks in its context instead (see Node::findInContext).
class BaseLink : public BaseParam {
public:
    using BaseParam::BaseParam;
    std::string typeName() const override { return "link to " + targetType(); }
    std::string defaultText() const override { return ""; }
    std::string valueText() const override { return m_path; }
    bool canBindTo(const BaseParam&) const override { return false; }
    void bindTo(const BaseParam*) override {}
    bool isComponentLink() const override { return true; }
    const std::string& targetPath() const { return m_path; }
    /// Sets the target; returns false when it has the wrong type.
    virtual bool setTarget(Component* c) = 0;
    virtual Component* targetComponent() const = 0;
    virtual std::string targetType() const = 0;

protected:
    void parseValue(const std::string& text, const SourceLoc& loc) override;
    std::string rangeProblem() const override { return {}; }
    std::string m_path;
};

std::string demangledTypeName(const char* mangled);

template <class T>
class Link : public BaseLink {
public:
    Link(Base* owner, ParamSpec spec) : BaseLink(owner, std::move(spec)) {}
    T* get() const { return m_target; }
    T* operator->() const { return m_target; }
    explicit operator bool() const { return m_target != nullptr; }
    bool setTarget(Component* c) override {
        m_target = dynamic_cast<T*>(c);
        if (m_target) markSet();
        return m_target != nullptr;
    }
    /// Sets the target from code.
    void set(T* t) { m_target = t; markSet(); }
    Component* targetComponent() const override { return m_target; }
    std::string targetType() const override { return demangledTypeName(typeid(T).name()); }

private:
    T* m_target = nullptr;
};

} // namespace fascia::core
