#include "VTKExporter.h"
#include "VTKXMLFile.h"
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace fs = std::filesystem;

namespace fascia::meshio {

void VTKExporter::init() {
    m_st = m_state.get() ? m_state.get() : node()->findInContext<core::BaseMechanicalState>();
    if (!m_st) fail("no MechanicalObject in its context: put one in the same node or link it with state=\"@...\"");
    m_base = m_filename.isSet() ? m_filename.get() : name();
    if (m_base.empty() || m_base.back() == '/') fail(m_filename, "filename must name files, e.g. \"liver\"");
    const fs::path pvd = fs::path(node()->context().outputDir) / (m_base + ".pvd");
    node()->context().claimOutput(pvd.string(), *this);
    removeStaleTemporaries(pvd.string(), fs::path(m_base).filename().string());  // what a killed run left
    // the element force fields acting on the state (for cells and cell data)
    m_forceFields.clear();
    node()->root()->visit([&](const core::Node& n) {
        for (auto* ff : n.findAllLocal<core::BaseForceField>())
            if (ff->node()->findInContext<core::BaseMechanicalState>() == m_st && (ff->tetrahedra() || ff->hexahedra()))
                m_forceFields.push_back(ff);
    });
    m_pvd.reset(pvd.string());
    m_lastStep = -1;
    m_surfaceNodes.clear();
    m_surfaceTriangles.clear();
    if (m_surface.get()) initSurface();
    m_toolOutput = ToolOutput();
    if (m_tools.get())
        m_toolOutput.start(*this, m_tools, *m_st, m_base, m_compression.get(),
                           m_surface.get() ? std::vector<std::string>{m_base + "_surface"} : std::vector<std::string>{});
}

void VTKExporter::initSurface() {
    const auto* topo = m_st->node()->findInContext<core::BaseTopology>();
    if (!topo || topo->meshData().points.size() != m_st->size() || topo->boundaryTriangles().empty())
        fail(m_surface, "surface=\"true\" needs the body's boundary: a mesh source with volume elements and as many nodes "
                        "as the state in the state's context (MeshLoader, GridMesh)");
    // the boundary nodes in index order, and the triangles renumbered over them
    const Triangles& b = topo->boundaryTriangles();
    std::vector<int> local(m_st->size(), -1);
    for (const auto& t : b)
        for (int n : t) local[size_t(n)] = 0;
    for (size_t i = 0; i < local.size(); ++i)
        if (local[i] == 0) {
            local[i] = int(m_surfaceNodes.size());
            m_surfaceNodes.push_back(int(i));
        }
    for (const auto& t : b) m_surfaceTriangles.push_back({local[size_t(t[0])], local[size_t(t[1])], local[size_t(t[2])]});
    m_surfaceSeries.start(*this, m_base + "_surface", m_compression.get());
}

std::vector<core::Component*> VTKExporter::dependencies() const {
    std::vector<core::Component*> out = BaseObserver::dependencies();
    if (m_tools.get() && node())
        for (core::BaseTool* t : node()->root()->findAllInSubtree<core::BaseTool>()) out.push_back(t);
    return out;
}

void VTKExporter::writeSurface(double t, long step) {
    const size_t n = m_surfaceNodes.size();
    m_surfacePoints.resize(n);
    m_surfaceDisplacement.resize(n);
    m_surfaceVelocity.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const size_t k = size_t(m_surfaceNodes[i]);
        m_surfacePoints[i] = m_st->x()[k];
        m_surfaceDisplacement[i] = m_st->x()[k] - m_st->x0()[k];
        m_surfaceVelocity[i] = m_st->v()[k];
    }
    SurfaceFrame frame;
    frame.points = &m_surfacePoints;
    frame.triangles = &m_surfaceTriangles;
    frame.arrays = {{"displacement", &m_surfaceDisplacement}, {"velocity", &m_surfaceVelocity}};
    frame.nodeIds = &m_surfaceNodes;
    m_surfaceSeries.write(t, step, frame);
}

void VTKExporter::observe(double t, long step) {
    if (step % m_every.get() != 0) return;
    writeStep(t, step);
}

void VTKExporter::observeFinal(double t, long step) {
    if (step != m_lastStep) writeStep(t, step);
}

namespace {

/// One force field's cells in the grid (ff null: the mesh source's).
struct Part {
    const Tetrahedra* tets = nullptr;
    const Hexahedra* hexes = nullptr;
    core::BaseForceField* ff = nullptr;
    size_t first = 0, count = 0;  ///< its cells in the grid
};

/// The cells of the grid, part by part, and how many there are in all.
struct Cells {
    std::vector<Part> parts;
    size_t count = 0;
};

/// The cells: the elements of every element force field on the state, in scene order (each one's
/// tetrahedra, then its hexahedra, the order of its cellData), else those of the mesh source.
Cells findCells(const std::vector<core::BaseForceField*>& forceFields, const core::Node& node, size_t n) {
    Cells c;
    for (auto* ff : forceFields) {
        Part p{ff->tetrahedra(), ff->hexahedra(), ff, c.count, 0};
        p.count = (p.tets ? p.tets->size() : 0) + (p.hexes ? p.hexes->size() : 0);
        c.count += p.count;
        c.parts.push_back(p);
    }
    if (c.parts.empty())
        if (auto* topo = node.findInContext<core::BaseTopology>(); topo && topo->meshData().points.size() == n) {
            Part p{&topo->meshData().tetrahedra, &topo->meshData().hexahedra, nullptr, 0, 0};
            p.count = p.tets->size() + p.hexes->size();
            c.count = p.count;
            c.parts.push_back(p);
        }
    return c;
}

/// The grid's points (the current positions) and cells; a vertex per node when there are no cells.
void addGeometry(vtkUnstructuredGrid* grid, const core::BaseMechanicalState& st, const Cells& c) {
    const size_t n = st.size();
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints(vtkIdType(n));
    for (size_t i = 0; i < n; ++i) pts->SetPoint(vtkIdType(i), st.x()[i].data());
    grid->SetPoints(pts);
    grid->Allocate(vtkIdType(c.count));
    for (const Part& p : c.parts) {
        if (p.tets)
            for (auto& e : *p.tets) {
                vtkIdType ids[4] = {e[0], e[1], e[2], e[3]};
                grid->InsertNextCell(10 /* VTK_TETRA */, 4, ids);
            }
        if (p.hexes)
            for (auto& e : *p.hexes) {
                vtkIdType ids[8] = {e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]};
                grid->InsertNextCell(12 /* VTK_HEXAHEDRON */, 8, ids);
            }
    }
    if (c.count == 0) {
        for (size_t i = 0; i < n; ++i) {
            vtkIdType id = vtkIdType(i);
            grid->InsertNextCell(1 /* VTK_VERTEX */, 1, &id);
        }
    }
}

/// The point data: displacement, velocity, force and reaction.
void addPointData(vtkUnstructuredGrid* grid, const core::BaseMechanicalState& st) {
    const size_t n = st.size();
    auto addPointVectors = [&](const char* name, auto&& value) {
        vtkNew<vtkDoubleArray> a;
        a->SetName(name);
        a->SetNumberOfComponents(3);
        a->SetNumberOfTuples(vtkIdType(n));
        for (size_t i = 0; i < n; ++i) {
            const Vec3 v = value(i);
            a->SetTuple(vtkIdType(i), v.data());
        }
        grid->GetPointData()->AddArray(a);
    };
    addPointVectors("displacement", [&](size_t i) { return Vec3(st.x()[i] - st.x0()[i]); });
    addPointVectors("velocity", [&](size_t i) { return st.v()[i]; });
    addPointVectors("force", [&](size_t i) { return st.f()[i]; });
    addPointVectors("reaction", [&](size_t i) { return st.reaction()[i]; });
}

/// The cell array "forceField": which force field a cell belongs to (its index among them, in
/// scene order), to threshold on in ParaView.
void addForceFieldIndex(vtkUnstructuredGrid* grid, const Cells& c) {
    vtkNew<vtkDoubleArray> a;
    a->SetName("forceField");
    a->SetNumberOfTuples(vtkIdType(c.count));
    for (size_t i = 0; i < c.parts.size(); ++i)
        for (size_t k = 0; k < c.parts[i].count; ++k) a->SetValue(vtkIdType(c.parts[i].first + k), double(i));
    grid->GetCellData()->AddArray(a);
}

/// The force fields' cell data: one array per quantity over all cells; cells of a force field that
/// does not offer it are NaN.
void addCellData(vtkUnstructuredGrid* grid, const core::BaseMechanicalState& st, const Cells& c) {
    std::vector<vtkSmartPointer<vtkDoubleArray>> arrays;
    for (const Part& p : c.parts) {
        if (!p.ff) continue;
        std::vector<core::CellField> fields;
        p.ff->cellData(st, fields);
        for (auto& f : fields) {
            if (f.components <= 0 || f.values.size() != size_t(f.components) * p.count) continue;
            auto find = [&](const std::string& name) -> vtkDoubleArray* {
                for (auto& x : arrays)
                    if (name == x->GetName()) return x;
                return nullptr;
            };
            // the same name with another shape: an array of its own ("J_name", then "J_name_2" ...)
            std::string name = f.name;
            vtkDoubleArray* a = find(name);
            for (int k = 1; a && a->GetNumberOfComponents() != f.components; ++k) {
                name = f.name + "_" + p.ff->name() + (k > 1 ? "_" + std::to_string(k) : "");
                a = find(name);
            }
            if (!a) {
                arrays.push_back(vtkSmartPointer<vtkDoubleArray>::New());
                a = arrays.back();
                a->SetName(name.c_str());
                a->SetNumberOfComponents(f.components);
                a->SetNumberOfTuples(vtkIdType(c.count));
                a->Fill(std::numeric_limits<double>::quiet_NaN());
            }
            for (size_t k = 0; k < p.count; ++k) a->SetTuple(vtkIdType(p.first + k), f.values.data() + k * f.components);
        }
    }
    for (auto& a : arrays) grid->GetCellData()->AddArray(a);
}

} // namespace

void VTKExporter::writeStep(double t, long step) {
    m_lastStep = step;
    const SeriesFile file = seriesFile(node()->context().outputDir, m_base, step, ".vtu");
    const Cells cells = findCells(m_forceFields, *node(), m_st->size());
    vtkNew<vtkUnstructuredGrid> grid;
    addGeometry(grid, *m_st, cells);
    addPointData(grid, *m_st);
    if (cells.parts.size() > 1 && cells.count > 0) addForceFieldIndex(grid, cells);
    if (m_cellData.get() && cells.count > 0) addCellData(grid, *m_st, cells);
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    if (const std::string e = writeXMLFileAtomically(*writer, grid, file.path, m_compression.get()); !e.empty()) failOutput(&m_filename, e);
    std::vector<std::string> parts{file.name};
    for (std::string& f : m_toolOutput.write(step)) parts.push_back(std::move(f));
    m_pvd.add(t, std::move(parts));
    if (m_surfaceSeries.started()) writeSurface(t, step);
}

void VTKExporter::saveState(core::StateWriter& out) const {
    m_pvd.saveState(out, "");
    out.put("lastStep", m_lastStep);
    if (m_surfaceSeries.started()) m_surfaceSeries.saveState(out, "surface.");
}

void VTKExporter::restoreState(core::StateReader& in) {
    m_pvd.restoreState(in, "", *this);
    m_lastStep = in.getLong("lastStep");
    if (m_surfaceSeries.started()) m_surfaceSeries.restoreState(in, "surface.");
}

void VTKExporter::cleanup() {
    if (!m_st) return;
    m_pvd.finish();
    if (m_surfaceSeries.started()) m_surfaceSeries.finish();
}

} // namespace fascia::meshio
