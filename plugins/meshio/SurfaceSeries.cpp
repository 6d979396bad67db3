#include "SurfaceSeries.h"
#include "VTKXMLFile.h"
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
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

namespace {

/// The frame's points and triangles as poly data.
void addSurface(vtkPolyData* poly, const SurfaceFrame& frame) {
    const Positions& p = *frame.points;
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
}

/// The frame's point arrays, its "nodeId" and its field data.
void addArrays(vtkPolyData* poly, const SurfaceFrame& frame) {
    const size_t n = frame.points->size();
    for (const auto& a : frame.arrays) {
        vtkNew<vtkDoubleArray> arr;
        arr->SetName(a.name);
        arr->SetNumberOfComponents(3);
        arr->SetNumberOfTuples(vtkIdType(n));
        for (size_t i = 0; i < n; ++i) arr->SetTuple(vtkIdType(i), (*a.values)[i].data());
        poly->GetPointData()->AddArray(arr);
    }
    if (frame.nodeIds) {
        vtkNew<vtkIdTypeArray> ids;
        ids->SetName("nodeId");
        ids->SetNumberOfTuples(vtkIdType(n));
        for (size_t i = 0; i < n; ++i) ids->SetValue(vtkIdType(i), (*frame.nodeIds)[i]);
        poly->GetPointData()->AddArray(ids);
    }
    for (const auto& f : frame.fields) {
        vtkNew<vtkDoubleArray> arr;
        arr->SetName(f.name);
        arr->SetNumberOfComponents(3);
        arr->InsertNextTuple(f.value.data());
        poly->GetFieldData()->AddArray(arr);
    }
}

} // namespace

void writeSurfaceFile(const core::Component& owner, const SurfaceFrame& frame, const fs::path& target, const std::string& compression) {
    vtkNew<vtkPolyData> poly;
    addSurface(poly, frame);
    addArrays(poly, frame);
    vtkNew<vtkXMLPolyDataWriter> writer;
    if (const std::string e = writeXMLFileAtomically(*writer, poly, target, compression); !e.empty()) owner.failOutput(nullptr, e);
}

void SurfaceSeries::write(double t, long step, const SurfaceFrame& frame) {
    m_lastStep = step;
    const SeriesFile file = seriesFile(m_dir, m_base, step, ".vtp");
    writeSurfaceFile(*m_owner, frame, file.path, m_compression);
    m_pvd.add(t, {file.name});
}

} // namespace fascia::meshio
