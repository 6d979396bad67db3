#pragma once
/// XML scenes -> node graph. Components never see TinyXML2.
#include "fascia/scene/Node.h"

#include <memory>
#include <string>
#include <vector>

namespace fascia::core {

/// One XML element with its location: the parsed form of a scene, before any component exists.
struct ElementSpec {
    std::string tag;
    SourceLoc loc;
    std::vector<std::pair<std::string, std::string>> attributes;  ///< in file order
    std::vector<ElementSpec> children;
};

/// Parses a file (with <include href="..."/> expanded); XML errors are located.
ElementSpec parseSceneFile(const std::string& path);
ElementSpec parseSceneString(const std::string& xml, const std::string& virtualName, const std::string& baseDir);

/// Builds the node graph: unknown tags and attributes, bad values, missing required parameters and
/// links to nothing are located errors. Loads <RequiredPlugin> first. Does not init.
std::unique_ptr<Node> buildScene(const ElementSpec& root);

} // namespace fascia::core
