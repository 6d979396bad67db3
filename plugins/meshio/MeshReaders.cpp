// readMesh: picks the reader by the file's extension, then validates what it read. The readers
// live one format per file (GmshReader, LegacyVTKReader, VTKReader, TetGenReader) on a shared TextScanner; the
// checks are in MeshValidation.cpp.
#include "MeshReaders.h"

#include "GmshReader.h"
#include "LegacyVTKReader.h"
#include "MeshBuilder.h"
#include "MeshValidation.h"
#include "ReaderSupport.h"
#include "TetGenReader.h"
#include "VTKReader.h"

#include <new>
#include <utility>

namespace fascia::meshio {

void checkMeshFile(const std::string& path) {
    using namespace detail;
    const std::string ext = lowerExtension(path);
    if (ext != ".msh" && ext != ".vtk" && ext != ".vtu" && ext != ".node" && ext != ".ele") {
        fail(path, 0,
             (ext.empty() ? std::string("mesh file '") + path + "' has no extension"
                          : "unknown mesh file extension '" + ext + "' of '" + path + "'") +
                 ": " + kSupportedFormats);
    }
    if (ext == ".node" || ext == ".ele") checkTetGenFiles(path);
    else checkReadable(path);
}

MeshData readMesh(const std::string& path, const ReadOptions& opt, ReadReport* report) {
    using namespace detail;
    checkMeshFile(path);
    ReadReport local;
    ReadReport& rep = report ? *report : local;
    rep = ReadReport{};
    MeshBuilder b;
    b.report = &rep;
    b.origin.nodeFile = b.origin.elementFile = path;
    const std::string ext = lowerExtension(path);
    try {
        if (ext == ".msh")
            readGmsh(path, b);
        else if (ext == ".vtk")
            readLegacyVtk(path, b);
        else if (ext == ".vtu")
            readVtu(path, b);
        else if (ext == ".node" || ext == ".ele")
            readTetGen(path, b);
    } catch (const std::bad_alloc&) {
        fail(path, 0, "mesh file '" + path + "' announces more records than fit in memory: its header is corrupt");
    }
    b.finishGroups();
    validate(b.mesh, b.origin, opt, rep);
    return std::move(b.mesh);
}

} // namespace fascia::meshio
