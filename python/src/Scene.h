#pragma once
/// Scenes between Python and the core: a scene is a tree of tuples
/// (tag, file, line, [(attribute, text), ...], [children]), the parsed form of an XML scene
/// (core::ElementSpec). XML files and strings are parsed into it; Python's fascia.Node builds it;
/// both become the same node graph through core::buildScene, so that a scene built in Python runs
/// bitwise as the same XML scene.
#include "fascia/scene/SceneLoader.h"

#include <pybind11/pybind11.h>

namespace fascia::python {

namespace py = pybind11;

core::ElementSpec specFromTree(const py::handle& tree);
py::tuple treeFromSpec(const core::ElementSpec& spec);
/// parse_file, parse_string, load_plugins, load_plugin, components, describe, component_params.
void bindScene(py::module_& m);

} // namespace fascia::python
