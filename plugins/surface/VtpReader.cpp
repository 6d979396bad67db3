// .vtp (VTK XML PolyData) surfaces, read with VTK's own reader after the checks of VtpLayout.h:
// VtpReader.h. The file's bytes are read once (readSurface) and handed to VTK as a string, so that
// VTK reads what was checked.
#include "VtpReader.h"
#include "VtkMessages.h"
#include "VtpLayout.h"
#include "fascia/surface/VtkXmlText.h"

#include <vtkCellArray.h>
#include <vtkDataArraySelection.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <climits>
#include <cmath>

namespace fascia::surface::detail {

namespace {

[[noreturn]] void failAt(const std::string& path, long long at, const std::string& message) {
    core::throwInputError(core::SourceLoc{path, 0, at}, message);
}

std::string points(long long n) { return std::to_string(n) + (n == 1 ? " point" : " points"); }


/// VTK's read of the checked bytes. The point and cell data arrays are not read: a surface needs
/// none of them, and VTK 9.1 trusts their data (plugins/meshio/VTUDataCheck.h lists how that
/// crashes it). Its complaints become one error, at the byte its XML parser names or at the file.
vtkSmartPointer<vtkPolyData> readWithVtk(const std::string& bytes, const std::string& path, VtkMessages& messages) {
    vtkNew<vtkXMLPolyDataReader> reader;
    messages.watch(reader);
    reader->ReadFromInputStringOn();
    reader->SetInputString(bytes);
    reader->UpdateInformation();  // lists the arrays, so that they can be left out
    reader->GetPointDataArraySelection()->DisableAllArrays();
    reader->GetCellDataArraySelection()->DisableAllArrays();
    if (!messages.any() && reader->GetErrorCode() == 0) reader->Update();
    if (messages.any() || reader->GetErrorCode() != 0) {
        const std::string text = messages.text();
        const std::string message = "VTK could not read the surface" + (text.empty() ? std::string() : ": " + text) +
                                    "; check that the file is a complete VTK XML PolyData (.vtp) file";
        if (const long long byte = vtkParserByte(text); byte >= 0) failAt(path, byte, message);
        core::throwInputError(core::SourceLoc{path, 0}, message);
    }
    return reader->GetOutput();
}

/// The points, each coordinate finite (located at its value in the file).
void convertPoints(vtkPolyData* poly, const std::string& text, const VtpLayout& l, TriangleSurface& s) {
    const vtkIdType n = poly->GetNumberOfPoints();
    if (n > INT_MAX) failAt(s.file, (long long)l.piece, "the surface has " + points(n) + ": more than Fascia's triangles can index");
    const VtpValueBytes where(text, l, l.points3);
    s.points.resize(size_t(n));
    for (vtkIdType i = 0; i < n; ++i) {
        double x[3];
        poly->GetPoint(i, x);
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(x[a]))
                failAt(s.file, where.at(3 * (unsigned long long)i + unsigned(a)),
                       "point " + std::to_string(i) + " has a non-finite " + "xyz"[a] + " coordinate (" + std::to_string(x[a]) + ")");
        s.points[size_t(i)] = Vec3(x[0], x[1], x[2]);
    }
}

/// The triangles of the cells of a section: a polygon is a fan around its first point (as an OBJ
/// face), a strip of n points gives n - 2 triangles, every second one turned so that all face
/// the way the first does. Each triangle's origin is the byte of its cell's first point.
void convertCells(vtkCellArray* cells, VtpSection k, const std::string& text, const VtpLayout& l, TriangleSurface& s) {
    const bool strip = k == kStrips;
    const VtpValueBytes where(text, l, l.cells[size_t(k)].connectivity);
    const vtkIdType nPoints = vtkIdType(s.points.size());
    vtkNew<vtkIdList> ids;
    unsigned long long first = 0;  // the connectivity value of the cell's first point
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c) {
        cells->GetCellAtId(c, ids);
        const vtkIdType m = ids->GetNumberOfIds();
        const long long at = where.at(first);
        auto cell = [&] { return std::string(strip ? "strip " : "polygon ") + std::to_string(c) + " of <" + kVtpSectionNames[k] + ">"; };
        if (m < 3) failAt(s.file, at, cell() + " has " + points(m) + ": a " + (strip ? "triangle strip" : "polygon") + " has at least 3");
        for (vtkIdType j = 0; j < m; ++j)
            if (ids->GetId(j) < 0 || ids->GetId(j) >= nPoints)
                failAt(s.file, where.at(first + (unsigned long long)j),
                       cell() + " names point " + std::to_string(ids->GetId(j)) + ", but the file has " + points(nPoints) +
                           " (0-based indices 0 to " + std::to_string(nPoints - 1) + ")");
        auto id = [&](vtkIdType j) { return int(ids->GetId(j)); };
        for (vtkIdType j = 2; j < m; ++j) {
            const std::array<int, 3> t = !strip ? std::array<int, 3>{id(0), id(j - 1), id(j)}
                                         : j % 2 == 0 ? std::array<int, 3>{id(j - 2), id(j - 1), id(j)}
                                                      : std::array<int, 3>{id(j - 1), id(j - 2), id(j)};
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
                if (strip) continue;  // strips repeat a point to turn or to join: no triangle there
                failAt(s.file, at, cell() + " uses a point twice (points " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " +
                                       std::to_string(t[2]) + " of its triangle " + std::to_string(j - 2) + "): it has no area; remove it");
            }
            s.triangles.push_back(t);
            s.origin.push_back(at);
        }
        first += (unsigned long long)m;
    }
}

} // namespace

void readVtp(const std::string& bytes, TriangleSurface& s) {
    s.format = "VTK XML PolyData";
    s.byteOffsets = true;
    const VtpLayout layout = scanVtp(bytes, s.file);  // before VTK allocates what the file announces
    VtkMessages messages;  // for the rest of the read: VTK prints nothing to the console
    checkVtpOffsets(bytes, layout, s.file);
    const vtkSmartPointer<vtkPolyData> poly = readWithVtk(bytes, s.file, messages);
    convertPoints(poly, bytes, layout, s);
    convertCells(poly->GetPolys(), kPolys, bytes, layout, s);
    convertCells(poly->GetStrips(), kStrips, bytes, layout, s);
    if (s.triangles.empty())
        failAt(s.file, (long long)layout.piece,
               "the surface has no triangles: its Piece has NumberOfPolys=\"" + std::to_string(layout.cells[kPolys].count) +
                   "\" and NumberOfStrips=\"" + std::to_string(layout.cells[kStrips].count) + "\" (vertices and lines make no surface)");
}

} // namespace fascia::surface::detail
