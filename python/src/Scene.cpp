#include "Scene.h"

#include "fascia/plugin/PluginManager.h"
#include "fascia/plugin/Registry.h"

#include <pybind11/stl.h>

namespace fascia::python {

core::ElementSpec specFromTree(const py::handle& tree) {
    auto t = py::reinterpret_borrow<py::tuple>(tree);
    if (t.size() != 5) throw py::value_error("a scene tree entry is (tag, file, line, attributes, children)");
    core::ElementSpec s;
    s.tag = t[0].cast<std::string>();
    s.loc.file = t[1].cast<std::string>();
    s.loc.line = t[2].cast<int>();
    for (auto a : t[3]) {
        auto kv = py::reinterpret_borrow<py::tuple>(a);
        s.attributes.emplace_back(kv[0].cast<std::string>(), kv[1].cast<std::string>());
    }
    for (auto c : t[4]) s.children.push_back(specFromTree(c));
    return s;
}

py::tuple treeFromSpec(const core::ElementSpec& spec) {
    py::list attrs, children;
    for (auto& [k, v] : spec.attributes) attrs.append(py::make_tuple(k, v));
    for (auto& c : spec.children) children.append(treeFromSpec(c));
    return py::make_tuple(spec.tag, spec.loc.file, spec.loc.line, attrs, children);
}

namespace {
/// (name, type, unit, required, output, link, help) of each parameter of a registered component.
py::list componentParams(const std::string& name) {
    core::PluginManager::instance().loadDefaultPlugins();
    const auto& reg = core::Registry::instance();
    std::unique_ptr<core::Base> c;
    if (name == "Node") {
        c = std::make_unique<core::Node>();
    } else {
        if (!reg.find(name)) core::describeComponent(name);  // (throws the error with the closest names)
        c = reg.create(name);
    }
    py::list out;
    for (core::BaseParam* p : c->params()) {
        const auto& s = p->spec();
        out.append(py::make_tuple(p->name(), p->typeName(), s.unitText, s.isRequired, s.isOutput, p->isComponentLink(),
                                  s.helpText));
    }
    return out;
}

py::dict components() {
    core::PluginManager::instance().loadDefaultPlugins();
    py::dict out;
    for (auto& [n, e] : core::Registry::instance().entries())
        out[py::str(n)] = py::make_tuple(e.plugin.empty() ? std::string("core") : e.plugin,
                                         e.description.substr(0, e.description.find('\n')));
    return out;
}
} // namespace

void bindScene(py::module_& m) {
    m.def("parse_file", [](const std::string& path) { return treeFromSpec(core::parseSceneFile(path)); },
          "The scene tree of an XML file (includes expanded).");
    m.def("parse_string",
          [](const std::string& xml, const std::string& name, const std::string& baseDir) {
              return treeFromSpec(core::parseSceneString(xml, name, baseDir));
          },
          py::arg("xml"), py::arg("name") = "<string>", py::arg("base_dir") = ".");
    m.def("load_plugins", [] { core::PluginManager::instance().loadDefaultPlugins(); },
          "Loads the built-in plugins and those of FASCIA_PLUGIN_PATH (once).");
    m.def("load_plugin",
          [](const std::string& nameOrPath) {
              core::PluginManager::instance().loadDefaultPlugins();
              const auto& p = core::PluginManager::instance().load(nameOrPath);
              return py::make_tuple(p.id, p.version, p.file);
          },
          "Loads one plugin by name or path, as <RequiredPlugin> does; returns (id, version, file).");
    m.def("components", &components, "Every registered component: name -> (plugin, summary).");
    m.def("describe",
          [](const std::string& name) {
              core::PluginManager::instance().loadDefaultPlugins();
              return core::describeComponent(name);
          },
          "What `fascia-run --describe NAME` prints.");
    m.def("component_params", &componentParams);
}

} // namespace fascia::python
