#include "BarycentricSurfaceMapping.h"
#include "TetLocator.h"
#include "fascia/base/Format.h"
#include "fascia/scene/Node.h"
#include "fascia/surface/TriangleSurface.h"

namespace fascia::meshio {

using core::formatNumber;

void BarycentricSurfaceMapping::init() {
    m_st = m_state.get() ? m_state.get() : node()->findInContext<core::BaseMechanicalState>();
    if (!m_st) fail("no MechanicalObject in its context: put one in the same node or link it with state=\"@...\"");
    const auto* topo = m_st->node()->findInContext<core::BaseTopology>();
    if (!topo || topo->meshData().points.size() != m_st->size())
        fail("the body needs its mesh source (MeshLoader, GridMesh) in its context, with as many nodes as the state");
    const Tetrahedra& tets = topo->meshData().tetrahedra;
    if (tets.empty()) fail("the body has no tetrahedra: the mapping locates the visual vertices in tetrahedra (a hexahedral mesh is not supported)");

    surface::TriangleSurface s;
    try {
        s = surface::readSurface(m_filename.get().resolved);
    } catch (const core::Error& e) {
        auto notes = e.notes();
        notes.push_back("read by " + className() + " '" + name() + "' at " + loc().str());
        throw core::Error(e.kind(), e.loc().empty() ? loc() : e.loc(), e.message(), notes);
    }
    m_rest = s.points;
    m_triangles = s.triangles;

    // the tetrahedra in the rest state (the state's x0, which may differ from the file's points)
    const Positions& X = m_st->x0();
    Vec3 lo = X[0], hi = X[0];
    for (const auto& p : X) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double limit = m_maxDistance.get() > 0 ? m_maxDistance.get() : 0.05 * (hi - lo).norm();
    const TetLocator locator(X, tets, topo->boundaryTriangles());
    const size_t n = m_rest.size();
    m_tet.assign(n, -1);
    m_nodes.assign(n, {});
    m_weights.assign(n, {});
    m_distance.assign(n, 0.0);
    core::forEachNode(long(n), [&](long v) {
        const TetLocation l = locator.locate(m_rest[size_t(v)]);
        m_tet[size_t(v)] = l.tetrahedron;
        m_weights[size_t(v)] = l.weights;
        m_distance[size_t(v)] = l.distance;
        if (l.tetrahedron >= 0) m_nodes[size_t(v)] = tets[size_t(l.tetrahedron)];
    });
    for (size_t v = 0; v < n; ++v) {
        if (m_tet[v] < 0) fail(m_filename, "vertex " + std::to_string(v + 1) + " of '" + m_filename.get().written + "' lies in no tetrahedron and near no boundary triangle of the body");
        if (m_distance[v] > limit)
            fail(m_filename, "vertex " + std::to_string(v + 1) + " of '" + m_filename.get().written + "' at (" +
                                 formatNumber(m_rest[v][0], 4) + " " + formatNumber(m_rest[v][1], 4) + " " +
                                 formatNumber(m_rest[v][2], 4) + ") is " + formatNumber(m_distance[v], 4) +
                                 " m from the body, more than maxDistance = " + formatNumber(limit, 4) +
                                 " m: is the surface in the body's rest coordinates (same units, same place)?");
    }
    m_points.assign(n, Vec3::Zero());
    m_displacement.assign(n, Vec3::Zero());
    update();
    if (!m_output.get().empty()) {
#if FASCIA_MESHIO_WITH_VTK
        m_series.start(*this, m_output.get(), "lz4");
#else
        fail(m_output, "this build has no VTK support: the .vtp series cannot be written (rebuild with FASCIA_WITH_VTK=ON, or leave output empty)");
#endif
    }
}

void BarycentricSurfaceMapping::update() {
    const double* x = core::flat(m_st->x());
    core::forEachNodeRange(long(m_points.size()), [&](long lo, long hi) {
        for (long v = lo; v < hi; ++v) {
            const auto& nd = m_nodes[size_t(v)];
            const auto& w = m_weights[size_t(v)];
            for (int a = 0; a < 3; ++a)
                m_points[size_t(v)][a] = w[0] * x[3 * nd[0] + a] + w[1] * x[3 * nd[1] + a] + w[2] * x[3 * nd[2] + a] + w[3] * x[3 * nd[3] + a];
        }
    });
}

void BarycentricSurfaceMapping::write(double t, long step) {
#if FASCIA_MESHIO_WITH_VTK
    for (size_t v = 0; v < m_points.size(); ++v) m_displacement[v] = m_points[v] - m_rest[v];
    SurfaceFrame frame;
    frame.points = &m_points;
    frame.triangles = &m_triangles;
    frame.arrays = {{"displacement", &m_displacement}};
    m_series.write(t, step, frame);
#else
    (void)t;
    (void)step;
#endif
}

void BarycentricSurfaceMapping::observe(double t, long step) {
    update();
    if (m_series.started() && step % m_every.get() == 0) write(t, step);
}

void BarycentricSurfaceMapping::observeFinal(double t, long step) {
    update();
    if (m_series.started() && step != m_series.lastStep()) write(t, step);
}

void BarycentricSurfaceMapping::saveState(core::StateWriter& out) const {
#if FASCIA_MESHIO_WITH_VTK  // without VTK there is no series (SurfaceSeries.cpp is not built)
    if (m_series.started()) m_series.saveState(out, "");
#else
    (void)out;
#endif
}

void BarycentricSurfaceMapping::restoreState(core::StateReader& in) {
#if FASCIA_MESHIO_WITH_VTK
    if (m_series.started()) m_series.restoreState(in, "");
#else
    (void)in;
#endif
}

void BarycentricSurfaceMapping::cleanup() {
    if (m_series.started()) m_series.finish();
}

} // namespace fascia::meshio
