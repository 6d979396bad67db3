#include "VTKReader.h"
#include "ReaderSupport.h"
#include "VTKCells.h"
#include "VTUDataCheck.h"
#include "VTUHeaderCheck.h"
#include "fascia/surface/VtkXmlText.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <vector>

namespace fascia::meshio::detail {
namespace {

/// Collects VTK's error messages, and warnings that report read errors; prints nothing.
class CapturingOutputWindow : public vtkOutputWindow {
public:
    static CapturingOutputWindow* New();
    vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
    void DisplayText(const char*) override {}
    void DisplayErrorText(const char* text) override {
        if (text) errors.emplace_back(text);
    }
    void DisplayWarningText(const char* text) override { warning(text); }
    void DisplayGenericWarningText(const char* text) override { warning(text); }
    void DisplayDebugText(const char*) override {}
    std::vector<std::string> errors;

protected:
    CapturingOutputWindow() = default;

private:
    void warning(const char* text) {
        // the legacy reader reports bad or missing data ("Error reading ascii data...") as a warning
        if (text && std::strstr(text, "rror")) errors.emplace_back(text);
    }
};
vtkStandardNewMacro(CapturingOutputWindow)

/// VTK's readers print their errors and return an empty output instead of throwing. While a catcher
/// lives, VTK's messages go to it instead of the console (output window and vtkLogger's stderr);
/// errors() says what went wrong.
class VtkMessageCatcher {
public:
    VtkMessageCatcher()
        : m_previous(vtkOutputWindow::GetInstance()), m_display(vtkObject::GetGlobalWarningDisplay()),
          m_logVerbosity(vtkLogger::GetCurrentVerbosityCutoff()) {
        vtkObject::GlobalWarningDisplayOn();  // off would drop the messages before our observers see them
        vtkOutputWindow::SetInstance(m_window);
        // messages of objects nobody observes (the XML parser, the pipeline) also go to vtkLogger
        vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
        m_callback->SetClientData(this);
        m_callback->SetCallback(&VtkMessageCatcher::onMessage);
    }
    ~VtkMessageCatcher() {
        vtkLogger::SetStderrVerbosity(m_logVerbosity);
        vtkOutputWindow::SetInstance(m_previous);
        vtkObject::SetGlobalWarningDisplay(m_display);
    }
    VtkMessageCatcher(const VtkMessageCatcher&) = delete;
    VtkMessageCatcher& operator=(const VtkMessageCatcher&) = delete;

    void watch(vtkObject* obj) {
        obj->AddObserver(vtkCommand::ErrorEvent, m_callback);
        obj->AddObserver(vtkCommand::WarningEvent, m_callback);
    }
    bool hasErrors() const { return !m_errors.empty() || !m_window->errors.empty(); }
    std::string errors() const {
        std::vector<std::string> all = m_errors;
        for (const auto& e : m_window->errors) all.push_back(clean(e));
        std::string out;
        for (const auto& e : all)
            if (!e.empty() && out.find(e) == std::string::npos) out += (out.empty() ? "" : "; ") + e;
        return out;
    }

private:
    /// VTK writes "ERROR: In /path/file.cxx, line N\nvtkClass (0x...): message\n..."; keeps the
    /// message's first line, and drops the pipeline's "returned failure for request" dumps.
    static std::string clean(std::string text) {
        if (text.compare(0, 6, "ERROR:") == 0 || text.compare(0, 8, "Warning:") == 0 ||
            text.compare(0, 15, "Generic Warning") == 0) {
            const auto nl = text.find('\n');
            text = nl == std::string::npos ? std::string() : text.substr(nl + 1);
        }
        const auto colon = text.find("): ");
        if (colon != std::string::npos && text.compare(0, 3, "vtk") == 0) text = text.substr(colon + 3);
        const auto nl = text.find('\n');
        if (nl != std::string::npos) text.resize(nl);
        while (!text.empty() && std::isspace((unsigned char)text.back())) text.pop_back();
        if (text.find("returned failure for request") != std::string::npos) return {};
        return text;
    }
    static void onMessage(vtkObject*, unsigned long event, void* self, void* callData) {
        auto* me = static_cast<VtkMessageCatcher*>(self);
        if (!callData) return;
        const char* text = static_cast<const char*>(callData);
        if (event == vtkCommand::ErrorEvent || std::strstr(text, "rror")) me->m_errors.push_back(clean(text));
    }

    vtkSmartPointer<vtkOutputWindow> m_previous;
    int m_display;
    vtkLogger::Verbosity m_logVerbosity;
    vtkNew<CapturingOutputWindow> m_window;
    vtkNew<vtkCallbackCommand> m_callback;
    std::vector<std::string> m_errors;
};


/// A .vtu through vtkXMLUnstructuredGridReader; VTK's complaints become a located error (at the
/// byte its XML parser names, else at the file: VTK's data errors say no more than the array).
vtkSmartPointer<vtkUnstructuredGrid> readXmlGrid(const std::string& path, VtkMessageCatcher& catcher) {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    catcher.watch(reader);
    if (!reader->CanReadFile(path.c_str()))
        fail(path, 0,
             "'" + path + "' is not a VTK XML unstructured grid: a .vtu file starts with <VTKFile "
             "type=\"UnstructuredGrid\" ...>; check that the file is complete and of the right kind");
    reader->SetFileName(path.c_str());
    reader->Update();
    if (catcher.hasErrors() || reader->GetErrorCode() != 0) {
        const std::string errors = catcher.hasErrors() ? catcher.errors() : std::string();
        const std::string message = "VTK could not read '" + path + "'" + (errors.empty() ? "" : ": " + errors) +
                                    "; check that the file is a complete VTK XML unstructured grid";
        if (const long long byte = surface::vtkParserByte(errors); byte >= 0) failAtByte(path, byte, message);
        fail(path, 0, message);
    }
    return reader->GetOutput();
}

/// Where the grid's cells and points are in the file (VtuLayout, vtuValueBytes): per cell the byte
/// of its first connectivity value, per point the byte of its x coordinate; a list is empty when the
/// layout does not give every item (the pieces' counts are not VTK's, an array of unknown type).
struct GridBytes {
    std::vector<long long> cells, points;
};
GridBytes locate(const VtuLayout& l, vtkUnstructuredGrid* grid) {
    GridBytes out;
    unsigned long long cells = 0, points = 0;
    for (const auto& p : l.pieces) cells += p.cells, points += p.points;
    auto complete = [](std::vector<long long>& v) {
        if (std::any_of(v.begin(), v.end(), [](long long b) { return b < 0; })) v.clear();
    };
    if (cells == (unsigned long long)grid->GetNumberOfCells()) {
        vtkIdType c = 0;
        std::vector<unsigned long long> first;
        for (const auto& p : l.pieces) {
            first.clear();
            unsigned long long k = 0;  // connectivity values of the piece before cell c
            for (unsigned long long i = 0; i < p.cells; ++i, ++c) {
                first.push_back(k);
                k += (unsigned long long)grid->GetCells()->GetCellSize(c);
            }
            const auto b = vtuValueBytes(l, p.connectivity, first);
            out.cells.insert(out.cells.end(), b.begin(), b.end());
        }
        complete(out.cells);
    }
    if (points == (unsigned long long)grid->GetNumberOfPoints()) {
        std::vector<unsigned long long> first;
        for (const auto& p : l.pieces) {
            first.clear();
            for (unsigned long long i = 0; i < p.points; ++i) first.push_back(3 * i);
            const auto b = vtuValueBytes(l, p.points3, first);
            out.points.insert(out.points.end(), b.begin(), b.end());
        }
        complete(out.points);
    }
    return out;
}

/// Points, kept cells with their groups, and the cell arrays of grid into b; the cells and points
/// located in the file by the layout (errors here and in the mesh validation: "file: byte N:").
void convertGrid(vtkUnstructuredGrid* grid, const std::string& path, const VtuLayout& layout, MeshBuilder& b) {
    const vtkIdType nPoints = grid->GetNumberOfPoints();
    const vtkIdType nCells = grid->GetNumberOfCells();
    if (nPoints == 0 && nCells == 0) {
        const std::string message = "'" + path + "' has no points and no cells: VTK read an empty grid; is the file complete?";
        if (!layout.pieces.empty()) failAtByte(path, (long long)layout.pieces.front().at, message);
        fail(path, 0, message + " (it has no <Piece>)");
    }
    const GridBytes where = locate(layout, grid);
    b.origin.nodeByte = where.points;
    auto& mesh = b.mesh;
    mesh.points.resize(size_t(nPoints));
    for (vtkIdType i = 0; i < nPoints; ++i) {
        double x[3];
        grid->GetPoint(i, x);
        mesh.points[size_t(i)] = Vec3(x[0], x[1], x[2]);
    }

    // physical groups
    vtkDataArray* groups = nullptr;
    vtkCellData* cd = grid->GetCellData();
    for (const char* gname : {"gmsh:physical", "CellEntityIds"}) {
        vtkDataArray* a = cd ? cd->GetArray(gname) : nullptr;
        if (a && a->GetNumberOfComponents() == 1 && a->GetNumberOfTuples() == nCells) {
            groups = a;
            break;
        }
    }

    vtkNew<vtkIdList> ids;
    std::vector<int> nodes;
    for (vtkIdType c = 0; c < nCells; ++c) {
        const int type = grid->GetCellType(c);
        grid->GetCellPoints(c, ids);
        nodes.resize(size_t(ids->GetNumberOfIds()));
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
            const vtkIdType v = ids->GetId(k);
            if (v < 0 || v >= nPoints) {
                const std::string message = "cell " + std::to_string(c) + " names point " + std::to_string(v) +
                                            ", but the file has " + plural(nPoints, "point") + " (0-based indices 0 to " +
                                            std::to_string(nPoints - 1) + ")";
                if (!where.cells.empty()) failAtByte(path, where.cells[size_t(c)], message);
                fail(path, 0, message);
            }
            nodes[size_t(k)] = int(v);
        }
        const int group = groups ? int(std::lround(groups->GetComponent(c, 0))) : 0;
        addVtkCell(b, c, type, nodes.data(), nodes.size(), group, 0, where.cells.empty() ? -1 : where.cells[size_t(c)]);
    }

    // per-cell arrays with 1 or 3 components, restricted to the volume cells (tets first, then hexes)
    if (cd) {
        std::vector<double> values;
        for (int a = 0; a < cd->GetNumberOfArrays(); ++a) {
            vtkDataArray* arr = cd->GetArray(a);
            if (!arr || !arr->GetName() || arr->GetNumberOfTuples() != nCells) continue;
            const int nc = arr->GetNumberOfComponents();
            if (nc != 1 && nc != 3) continue;
            values.resize(size_t(nCells) * size_t(nc));
            for (vtkIdType c = 0; c < nCells; ++c)
                for (int k = 0; k < nc; ++k) values[size_t(c) * size_t(nc) + size_t(k)] = arr->GetComponent(c, k);
            addVtkCellArray(b, arr->GetName(), nc, values.data());
        }
    }
}

} // namespace

void readVtu(const std::string& path, MeshBuilder& b) {
    checkReadable(path);
    const VtuLayout layout = checkVtuHeaders(path);  // before VTK allocates what the file announces
    b.origin.elementWord = "cell";
    VtkMessageCatcher catcher;  // for the whole read: VTK prints nothing to the console
    checkVtuData(path, layout);  // the arrays VTK would read wrongly
    b.report->format = "VTK XML";
    const vtkSmartPointer<vtkUnstructuredGrid> grid = readXmlGrid(path, catcher);
    convertGrid(grid, path, layout, b);
}

} // namespace fascia::meshio::detail
