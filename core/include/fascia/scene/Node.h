#pragma once
/// The scene graph: nodes with children and components.
#include "fascia/base/Component.h"
#include "fascia/sim/LoadCurve.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fascia::core {

struct MechanicalGroup;

/// Per-run settings shared by the components of one scene (held by its root node).
struct SceneContext {
    std::string sceneFile;     ///< file the scene came from ("" when built in code)
    std::string outputDir = "."; ///< folder observers write into
    double time = 0.0, dt = 0.0;
    long step = 0;
    /// The mechanical groups the simulation assembled (set by Simulation::init; null before), for
    /// observers that evaluate a group's forces (a Monitor's residual).
    std::vector<MechanicalGroup>* groups = nullptr;
    /// Output files already claimed by a component (path -> who), so that two exporters never
    /// write over each other's files.
    std::map<std::string, std::string> outputs;
    /// Claims an output file for `who`, checked before anything is written: a located input error
    /// when the path names a folder, leaves the output folder ('..', an absolute path) or another
    /// component has it; a located output error (exit code 1) when it cannot be created (its nearest
    /// existing folder is a file or not writable).
    void claimOutput(const std::string& path, const Base& who);
};

class Node : public Base {
public:
    Node();
    explicit Node(const std::string& name);
    ~Node() override;

    Node* parent() const { return m_parent; }
    Node* root();
    std::string path() const override;

    Node& addChild(std::unique_ptr<Node> child);
    Node& addChild(const std::string& name);
    Component& addComponent(std::unique_ptr<Component> c);
    /// Creates a component in code: `auto& mo = node.add<MechanicalObject>("mo");`
    template <class T, class... A> T& add(const std::string& name, A&&... args) {
        auto c = std::make_unique<T>(std::forward<A>(args)...);
        c->setName(name);
        return static_cast<T&>(addComponent(std::move(c)));
    }

    const std::vector<std::unique_ptr<Node>>& children() const { return m_children; }
    const std::vector<std::unique_ptr<Component>>& components() const { return m_components; }

    Node* child(const std::string& name) const;
    Component* component(const std::string& name) const;

    /// First component of type T in this node.
    template <class T> T* findLocal() const {
        for (auto& c : m_components)
            if (auto* t = dynamic_cast<T*>(c.get())) return t;
        return nullptr;
    }
    /// All components of type T in this node.
    template <class T> std::vector<T*> findAllLocal() const {
        std::vector<T*> out;
        for (auto& c : m_components)
            if (auto* t = dynamic_cast<T*>(c.get())) out.push_back(t);
        return out;
    }
    /// First component of type T in this node or, failing that, in its ancestors (the context).
    template <class T> T* findInContext() const {
        for (const Node* n = this; n; n = n->m_parent)
            if (auto* t = n->findLocal<T>()) return t;
        return nullptr;
    }
    /// All components of type T in this subtree, depth first, in declaration order.
    template <class T> std::vector<T*> findAllInSubtree() const {
        std::vector<T*> out;
        visit([&](const Node& n) { for (auto* t : n.findAllLocal<T>()) out.push_back(t); });
        return out;
    }
    /// A component by name anywhere in the tree (first match, depth first).
    Component* findByName(const std::string& name) const;
    /// A component by path ("a/b/mo", see resolveComponent) or by a name that must be unique in this
    /// subtree: an ambiguous name is an InputError naming the first match's path; null when none.
    Component* findUnique(const std::string& nameOrPath) const;
    /// Resolves a path relative to this node: "mo", "../loader", "child/mo", "/root/child/mo".
    /// A bare name not in this node is looked up in the ancestors. Returns null when nothing matches.
    Component* resolveComponent(const std::string& path) const;
    Node* resolveNode(const std::string& path) const;

    template <class F> void visit(F&& f) const {
        f(*this);
        for (auto& c : m_children) c->visit(f);
    }

    // parameters of a node
    Param<TimeStep> dt{this, ParamSpec("dt").unit("s").help("time step, or \"auto\" for the smallest stable step of the force fields times dtSafety (root node)")};
    Param<double> dtSafety{this, ParamSpec("dtSafety").above(0).max(1).help("safety factor applied to the critical time step when dt=\"auto\" (the critical step is computed at rest; large compression of a nearly incompressible material raises the wave speed, e.g. 1.4 times at 30 %: keep 0.5 or less there)"), 0.5};
    Param<Vec3> gravity{this, ParamSpec("gravity").unit("m/s^2").help("gravity acceleration, inherited by child nodes that do not set it"), Vec3::Zero()};
    CurveParam gravityCurve{this, curveSpec("gravityCurve", "this node's gravity, g(t) = c(t) gravity (with gravity, inherited with it)")};
    Param<double> endTime{this, ParamSpec("endTime").unit("s").min(0).help("simulated time fascia-run runs to, exactly (the last step shortened to end on it), when neither --steps nor --time is given (0: 100 steps)"), 0.0};

    /// The run's shared context (on the root node).
    SceneContext& context();

    /// Gravity of the nearest node (this or an ancestor) that sets it.
    Vec3 contextGravity() const;
    /// The load curve of that node's gravity (the constant 1 when it has none).
    const Curve& contextGravityCurve() const;

private:
    Node* m_parent = nullptr;
    std::unique_ptr<SceneContext> m_context;
    std::vector<std::unique_ptr<Node>> m_children;
    std::vector<std::unique_ptr<Component>> m_components;
};

} // namespace fascia::core
