#include "MeshLoader.h"
#include "MeshReaders.h"

#include <Eigen/Geometry>

#include <cmath>

namespace fascia::meshio {

void MeshLoader::init() {
    ReadOptions opt;
    opt.fixOrientation = m_fixOrientation.get();
    ReadReport report;
    MeshData mesh;
    try {
        checkMeshFile(m_filename.get().resolved);
    } catch (const core::Error& e) {
        // no place in the mesh file is at fault: the error is where the scene names the file
        fail(m_filename, e.message(), e.notes());
    }
    try {
        mesh = readMesh(m_filename.get().resolved, opt, &report);
    } catch (const core::Error& e) {
        // the reader's location is inside the mesh file; add where the scene asked for it
        auto notes = e.notes();
        notes.push_back("read by " + className() + " '" + name() + "' at " + loc().str());
        throw core::Error(e.kind(), e.loc().empty() ? loc() : e.loc(), e.message(), notes);
    }
    m_flipped = report.flippedElements;
    if (m_flipped > 0) warn("flipped " + std::to_string(m_flipped) + " inverted element(s) of '" + m_filename.get().written + "'");
    const double deg = M_PI / 180.0;
    const Vec3 r = m_rotation.get() * deg;
    const Mat3 R = (Eigen::AngleAxisd(r[2], Vec3::UnitZ()) * Eigen::AngleAxisd(r[1], Vec3::UnitY()) *
                    Eigen::AngleAxisd(r[0], Vec3::UnitX()))
                       .toRotationMatrix();
    const double s = m_scale.get();
    const Vec3 t = m_translation.get();
    if (s != 1.0 || !r.isZero() || !t.isZero())
        for (auto& p : mesh.points) p = R * (s * p) + t;
    publish(std::move(mesh));
}

} // namespace fascia::meshio
