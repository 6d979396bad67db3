#include "VTKExporter.h"
#include "fascia/scene/Node.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace fascia::meshio {

void writeFileAtomically(const std::string& path, const std::string& text) {
    const fs::path p(path);
    const fs::path tmp = p.parent_path() / ("." + p.filename().string() + ".tmp");
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) throw core::Error(core::ErrorKind::Internal, {}, "cannot write '" + tmp.string() + "' (disk full or no permission?)");
    }
    std::error_code ec;
    fs::rename(tmp, p, ec);
    if (ec) throw core::Error(core::ErrorKind::Internal, {}, "cannot rename '" + tmp.string() + "' to '" + path + "': " + ec.message());
}

void VTKExporter::init() {
    m_st = m_state.get() ? m_state.get() : node()->findInContext<core::BaseMechanicalState>();
    if (!m_st) fail("no MechanicalObject in its context: put one in the same node or link it with state=\"@...\"");
    m_base = m_filename.isSet() ? m_filename.get() : name();
    if (m_base.empty() || m_base.back() == '/') fail(m_filename, "filename must name files, e.g. \"liver\"");
    const fs::path pvd = fs::path(node()->context().outputDir) / (m_base + ".pvd");
    node()->context().claimOutput(pvd.string(), *this);
    // temporary files a killed run left behind
    std::error_code ec;
    const std::string stem = "." + fs::path(m_base).filename().string() + "_";
    for (auto& e : fs::directory_iterator(pvd.parent_path().empty() ? fs::path(".") : pvd.parent_path(), ec)) {
        const std::string n = e.path().filename().string();
        if ((n.rfind(stem, 0) == 0 || n == "." + pvd.filename().string() + ".tmp") && e.path().extension() == ".tmp")
            fs::remove(e.path(), ec);
    }
    // the element force fields acting on the state (for cells and cell data)
    m_forceFields.clear();
    node()->root()->visit([&](const core::Node& n) {
        for (auto* ff : n.findAllLocal<core::BaseForceField>())
            if (ff->node()->findInContext<core::BaseMechanicalState>() == m_st && (ff->tetrahedra() || ff->hexahedra()))
                m_forceFields.push_back(ff);
    });
    if (m_forceFields.size() > 1)
        warn("writes the cells of '" + m_forceFields.front()->name() + "' only; " + std::to_string(m_forceFields.size() - 1) +
             " other element force field(s) on the same state are not exported");
    m_written.clear();
    m_listed = 0;
    m_lastCollection = 0;
}

void VTKExporter::observe(double t, long step) {
    if (step % m_every.get() != 0) return;
    writeStep(t, step);
}

void VTKExporter::writeStep(double t, long step) {
    const std::string dir = node()->context().outputDir;
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, "_%06ld.vtu", step);
    const std::string fileName = fs::path(m_base).filename().string() + suffix;
    const fs::path target = fs::path(dir) / fs::path(m_base).parent_path() / fileName;
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);

    const size_t n = m_st->size();
    vtkNew<vtkUnstructuredGrid> grid;
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints(vtkIdType(n));
    for (size_t i = 0; i < n; ++i) pts->SetPoint(vtkIdType(i), m_st->x()[i].data());
    grid->SetPoints(pts);

    // cells: the elements of the force fields (first one that has them), else those of the mesh source
    const Tetrahedra* tets = nullptr;
    const Hexahedra* hexes = nullptr;
    core::BaseForceField* cellOwner = nullptr;
    for (auto* ff : m_forceFields) {
        tets = ff->tetrahedra();
        hexes = ff->hexahedra();
        cellOwner = ff;
        break;
    }
    if (!cellOwner)
        if (auto* topo = node()->findInContext<core::BaseTopology>(); topo && topo->meshData().points.size() == n) {
            tets = &topo->meshData().tetrahedra;
            hexes = &topo->meshData().hexahedra;
        }
    const size_t nt = tets ? tets->size() : 0, nh = hexes ? hexes->size() : 0;
    grid->Allocate(vtkIdType(nt + nh));
    if (tets)
        for (auto& e : *tets) {
            vtkIdType ids[4] = {e[0], e[1], e[2], e[3]};
            grid->InsertNextCell(10 /* VTK_TETRA */, 4, ids);
        }
    if (hexes)
        for (auto& e : *hexes) {
            vtkIdType ids[8] = {e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]};
            grid->InsertNextCell(12 /* VTK_HEXAHEDRON */, 8, ids);
        }
    if (nt + nh == 0) {
        for (size_t i = 0; i < n; ++i) {
            vtkIdType id = vtkIdType(i);
            grid->InsertNextCell(1 /* VTK_VERTEX */, 1, &id);
        }
    }

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
    addPointVectors("displacement", [&](size_t i) { return Vec3(m_st->x()[i] - m_st->x0()[i]); });
    addPointVectors("velocity", [&](size_t i) { return m_st->v()[i]; });
    addPointVectors("force", [&](size_t i) { return m_st->f()[i]; });
    addPointVectors("reaction", [&](size_t i) { return m_st->reaction()[i]; });

    if (m_cellData.get() && cellOwner) {
        std::vector<core::CellField> fields;
        cellOwner->cellData(*m_st, fields);
        const size_t cells = nt + nh;
        for (auto& f : fields) {
            if (f.components <= 0 || f.values.size() != size_t(f.components) * cells) continue;
            vtkNew<vtkDoubleArray> a;
            a->SetName(f.name.c_str());
            a->SetNumberOfComponents(f.components);
            a->SetNumberOfTuples(vtkIdType(cells));
            for (size_t c = 0; c < cells; ++c) a->SetTuple(vtkIdType(c), f.values.data() + c * f.components);
            grid->GetCellData()->AddArray(a);
        }
    }

    const fs::path tmp = target.parent_path() / ("." + target.filename().string() + ".tmp");
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(tmp.string().c_str());
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    const std::string& compression = m_compression.get();
    if (compression == "lz4") writer->SetCompressorTypeToLZ4();
    else if (compression == "zlib") writer->SetCompressorTypeToZLib();
    else writer->SetCompressorTypeToNone();
    if (writer->Write() != 1) {
        fs::remove(tmp, ec);
        throw core::Error(core::ErrorKind::Internal, loc(), className() + " '" + name() + "': cannot write '" + target.string() +
                                         "' (disk full, or no permission on the output folder?)");
    }
    fs::rename(tmp, target, ec);
    if (ec) throw core::Error(core::ErrorKind::Internal, loc(), "cannot rename '" + tmp.string() + "': " + ec.message());
    m_written.emplace_back(t, (fs::path(m_base).parent_path() / fileName).string());
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    if (m_written.size() <= 100 || now - m_lastCollection >= 1.0) {
        writeCollection();
        m_lastCollection = now;
    }
}

void VTKExporter::cleanup() {
    if (m_st && m_written.size() != m_listed) writeCollection();
}

void VTKExporter::writeCollection() {
    std::ostringstream s;
    s.precision(17);
    s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (auto& [t, f] : m_written)
        s << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << fs::path(f).filename().string() << "\"/>\n";
    s << "  </Collection>\n</VTKFile>\n";
    writeFileAtomically((fs::path(node()->context().outputDir) / (m_base + ".pvd")).string(), s.str());
    m_listed = m_written.size();
}

} // namespace fascia::meshio
