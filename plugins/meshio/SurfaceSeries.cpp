#include "SurfaceSeries.h"
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <filesystem>

namespace fs = std::filesystem;

namespace fascia::meshio {

void SurfaceSeries::start(const core::Component& owner, const std::string& base, const std::string& compression) {
    m_owner = &owner;
    m_base = base;
    m_compression = compression;
    m_dir = owner.node()->context().outputDir;
    const fs::path pvd = fs::path(m_dir) / (m_base + ".pvd");
    owner.node()->context().claimOutput(pvd.string(), owner);
    removeStaleTemporaries(pvd.string(), fs::path(m_base).filename().string());
    m_pvd.reset(pvd.string());
    m_lastStep = -1;
}

void SurfaceSeries::saveState(core::StateWriter& out, const std::string& prefix) const {
    m_pvd.saveState(out, prefix);
    out.put(prefix + "lastStep", m_lastStep);
}

void SurfaceSeries::restoreState(core::StateReader& in, const std::string& prefix) {
    m_pvd.restoreState(in, prefix, *m_owner);
    m_lastStep = in.getLong(prefix + "lastStep");
}

void SurfaceSeries::write(double t, long step, const SurfaceFrame& frame) {
    m_lastStep = step;
    const SeriesFile file = seriesFile(m_dir, m_base, step, ".vtp");
    const fs::path& target = file.path;
    std::error_code ec;

    const Positions& p = *frame.points;
    vtkNew<vtkPolyData> poly;
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints(vtkIdType(p.size()));
    for (size_t i = 0; i < p.size(); ++i) pts->SetPoint(vtkIdType(i), p[i].data());
    poly->SetPoints(pts);
    vtkNew<vtkCellArray> polys;
    for (const auto& tri : *frame.triangles) {
        const vtkIdType ids[3] = {tri[0], tri[1], tri[2]};
        polys->InsertNextCell(3, ids);
    }
    poly->SetPolys(polys);
    for (const auto& a : frame.arrays) {
        vtkNew<vtkDoubleArray> arr;
        arr->SetName(a.name);
        arr->SetNumberOfComponents(3);
        arr->SetNumberOfTuples(vtkIdType(p.size()));
        for (size_t i = 0; i < p.size(); ++i) arr->SetTuple(vtkIdType(i), (*a.values)[i].data());
        poly->GetPointData()->AddArray(arr);
    }
    if (frame.nodeIds) {
        vtkNew<vtkIdTypeArray> ids;
        ids->SetName("nodeId");
        ids->SetNumberOfTuples(vtkIdType(p.size()));
        for (size_t i = 0; i < p.size(); ++i) ids->SetValue(vtkIdType(i), (*frame.nodeIds)[i]);
        poly->GetPointData()->AddArray(ids);
    }

    const fs::path tmp = target.parent_path() / ("." + target.filename().string() + ".tmp");
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(tmp.string().c_str());
    writer->SetInputData(poly);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    if (m_compression == "lz4") writer->SetCompressorTypeToLZ4();
    else if (m_compression == "zlib") writer->SetCompressorTypeToZLib();
    else writer->SetCompressorTypeToNone();
    if (writer->Write() != 1) {
        fs::remove(tmp, ec);
        throw core::Error(core::ErrorKind::Output, m_owner->loc(), m_owner->className() + " '" + m_owner->name() + "': cannot write '" +
                                                                          target.string() + "' (disk full, or no permission on the output folder?)");
    }
    fs::rename(tmp, target, ec);
    if (ec) throw core::Error(core::ErrorKind::Output, m_owner->loc(), "cannot rename '" + tmp.string() + "': " + ec.message());
    m_pvd.add(t, file.name);
}

} // namespace fascia::meshio
