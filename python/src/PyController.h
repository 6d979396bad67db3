#pragma once
/// PythonController: a component whose steps call a Python object, registered by the module (a
/// scene that names it runs from Python: fascia.load, fascia.Simulation). Its object is either given
/// from Python (fascia.Node.add(MyController(...)) hands it over by `object`) or made at init from
/// `controller` ("module.Class", or "file.py:Class" with the file relative to the scene) and `args`
/// (keyword arguments, "depth=0.01 name='a'"). The hooks, each optional:
///   on_init(sim)            after the scene is built, before any step
///   on_step_begin(sim, t)   at the start of every step, before any force (Component::beginStep)
///   on_step_end(sim, t)     after every step, with the observers (BaseObserver::observe)
/// A hook that raises, or returns anything but None, fails the step: a fascia.ControllerError whose
/// cause is the hook's exception, with its traceback.
#include "Holder.h"

#include "fascia/sim/Mechanics.h"

namespace fascia::python {

class PyController : public core::BaseObserver {
public:
    PyController();
    ~PyController() override;
    void init() override;
    void beginStep(double t, double dt) override;
    void observe(double t, long step) override;
    bool records(long step) const override { return step > 0 && m_end; }
    /// Hands it the holder and the Python simulation (a weak reference), after the build.
    void attach(Holder* h, py::object simWeak);
    /// Calls on_init (from the build, with the GIL held).
    void callInit();
    const py::object& object() const { return m_object; }

    core::Param<std::string> m_controller{this, core::ParamSpec("controller").help("the Python class: \"module.Class\" (importable) or \"file.py:Class\" (relative to the scene file)")};
    core::Param<std::string> m_args{this, core::ParamSpec("args").help("keyword arguments of the class, as Python literals: \"depth=0.01 label='a'\"")};
    core::Param<int> m_objectId{this, core::ParamSpec("object").min(0).help("set by Python scenes: the controller object handed over by fascia.Node.add (its id in the hand-over table)"), 0};

private:
    /// Calls a hook (the GIL taken); an exception or a return value other than None fails the step.
    void call(const char* hook, const double* t);
    py::object m_object, m_begin, m_end, m_simWeak;
    Holder* m_holder = nullptr;
};

/// Registers PythonController and binds the hand-over table (_fascia.hand_over).
void bindController(py::module_& m);

} // namespace fascia::python
