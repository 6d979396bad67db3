#include "VTKXMLFile.h"

#include <vtkDataObject.h>
#include <vtkXMLWriter.h>

namespace fs = std::filesystem;

namespace fascia::meshio {

std::string writeXMLFileAtomically(vtkXMLWriter& writer, vtkDataObject* data, const fs::path& target,
                                   const std::string& compression) {
    std::error_code ec;
    const fs::path tmp = target.parent_path() / ("." + target.filename().string() + ".tmp");
    writer.SetFileName(tmp.string().c_str());
    writer.SetInputDataObject(data);
    writer.SetDataModeToAppended();
    writer.EncodeAppendedDataOff();
    if (compression == "lz4") writer.SetCompressorTypeToLZ4();
    else if (compression == "zlib") writer.SetCompressorTypeToZLib();
    else writer.SetCompressorTypeToNone();
    if (writer.Write() != 1) {
        fs::remove(tmp, ec);
        return "cannot write '" + target.string() + "' (disk full, or no permission on the output folder?)";
    }
    fs::rename(tmp, target, ec);
    return ec ? "cannot rename '" + tmp.string() + "': " + ec.message() : "";
}

} // namespace fascia::meshio
