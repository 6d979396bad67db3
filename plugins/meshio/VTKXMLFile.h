#pragma once
/// Writing one VTK XML file (.vtu, .vtp) atomically, shared by the exporters' series. Its .cpp
/// includes VTK; this header only names VTK's classes, so that its callers' other sources need none.
#include <filesystem>
#include <string>

class vtkDataObject;
class vtkXMLWriter;

namespace fascia::meshio {

/// Writes `data` with `writer` (appended raw data, compressed with "lz4", "zlib" or "none") to
/// `target` under a temporary name (".<name>.tmp" beside it), renamed when complete, so that a run
/// killed at any moment leaves only complete files. Returns "" or what failed, for the caller's
/// located output error.
std::string writeXMLFileAtomically(vtkXMLWriter& writer, vtkDataObject* data, const std::filesystem::path& target,
                                   const std::string& compression);

} // namespace fascia::meshio
