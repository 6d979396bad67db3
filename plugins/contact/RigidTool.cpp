#include "RigidTool.h"
#include "BoundaryNodes.h"
#include "fascia/base/Format.h"
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace fascia::contact {

using core::formatNumber;

namespace {
/// Contact tolerance: a node within this fraction of the body's size from the tool touches it. Above
/// the static solver's probing perturbation (DynamicRelaxation moves nodes by up to 1e-7 of the
/// body's size to estimate the stiffness), so that probing does not switch a pressed node's contact
/// off and read its whole contact force as stiffness; far below any deformation of interest.
constexpr double kTouch = 2e-7;

/// A pose as 7 doubles: position x y z, orientation w x y z.
void putPose(core::StateWriter& out, const std::string& name, const core::Pose& p) {
    const Eigen::Quaterniond& q = p.orientation;
    const double v[7] = {p.position.x(), p.position.y(), p.position.z(), q.w(), q.x(), q.y(), q.z()};
    out.put(name, v, 7);
}
core::Pose getPose(core::StateReader& in, const std::string& name) {
    double v[7];
    in.getInto(name, v, 7);
    core::Pose p;
    p.position = Vec3(v[0], v[1], v[2]);
    p.orientation = Eigen::Quaterniond(v[3], v[4], v[5], v[6]);
    return p;
}
} // namespace

RigidTool::RigidTool() = default;

void RigidTool::init() { initContact(); }

void RigidTool::initContact() {
    m_body = m_bodyLink.get() ? m_bodyLink.get() : node()->findInContext<core::BaseMechanicalState>();
    if (!m_body)
        fail("no body to touch: no MechanicalObject in its context and no body=\"@...\" link",
             {"link the body's state, e.g. body=\"@../liver/state\", or put the tool in the body's node"});
    m_motion.init(*this);
    m_muS = m_staticFriction.get();
    m_muK = m_kineticFriction.isSet() ? m_kineticFriction.get() : m_muS;
    if (m_muK > m_muS)
        fail(m_kineticFriction, "kineticFriction = " + formatNumber(m_muK, 6) + " is above staticFriction = " + formatNumber(m_muS, 6) +
                                    ": a sliding contact cannot hold more than a sticking one",
             {"give kineticFriction <= staticFriction"});
    // the surface nodes: the boundary of the body's mesh, else every node
    const size_t n = m_body->size();
    m_surface.clear();
    if (auto* topo = m_body->node()->findInContext<core::BaseTopology>(); topo && topo->meshData().points.size() == n)
        m_surface = boundaryNodes(topo->meshData());
    if (m_surface.empty())
        for (size_t i = 0; i < n; ++i) m_surface.push_back(int(i));
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : m_body->x0()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double diag = n ? (hi - lo).norm() : 0.0;
    m_tolerance = kTouch * (diag > 0 ? diag : size());
    m_contact.assign(n, Vec3::Zero());
    m_slip.assign(n, 0);
    m_slipDir.assign(n, Vec3::Zero());
    m_anchor.assign(n, Vec3::Zero());
    m_memo.assign(memoizeDistance() ? n : 0, DistanceMemo{Vec3::Zero(), Vec3::Zero(), 0.0, false});
    m_active.clear();
    m_poseTime = m_prevTime = node()->context().time;
    m_pose = m_prevPose = m_hasSet ? m_set : m_motion.at(m_poseTime);
}

void RigidTool::saveState(core::StateWriter& out) const {
    putPose(out, "pose", m_pose);
    putPose(out, "prevPose", m_prevPose);
    out.put("poseTime", m_poseTime);
    out.put("prevTime", m_prevTime);
    out.put("hasSet", m_hasSet);
    putPose(out, "setPose", m_set);
    out.put("stepped", m_stepped);
    out.put("force", m_force.data(), 3);
    out.put("torque", m_torque.data(), 3);
    out.put("contact", m_contact);
    out.put("active", std::vector<double>(m_active.begin(), m_active.end()));  // node indices: exact as doubles
    out.put("slip", std::string(m_slip.begin(), m_slip.end()));
    out.put("slipDir", m_slipDir);
}

void RigidTool::restoreState(core::StateReader& in) {
    m_pose = getPose(in, "pose");
    m_prevPose = getPose(in, "prevPose");
    m_poseTime = in.getDouble("poseTime");
    m_prevTime = in.getDouble("prevTime");
    m_hasSet = in.getBool("hasSet");
    m_set = getPose(in, "setPose");
    m_stepped = in.getBool("stepped");
    in.getInto("force", m_force.data(), 3);
    in.getInto("torque", m_torque.data(), 3);
    in.getInto("contact", m_contact);
    const std::vector<double> active = in.getDoubles("active");
    const std::string slip = in.getText("slip");
    if (slip.size() != m_slip.size())
        in.fail("[" + path() + "] record 'slip' has " + std::to_string(slip.size()) + " values, this scene needs " +
                std::to_string(m_slip.size()));
    m_active.clear();
    for (double a : active) {
        if (!(a >= 0 && a < double(m_contact.size()) && a == std::floor(a)))
            in.fail("[" + path() + "] record 'active' holds " + formatNumber(a, 6) + ", not a node of the body");
        m_active.push_back(int(a));
    }
    m_slip.assign(slip.begin(), slip.end());
    in.getInto("slipDir", m_slipDir);
}

void RigidTool::setPose(const core::Pose& pose) {
    m_set = pose;
    m_set.orientation.normalize();
    m_hasSet = true;
    if (!m_stepped) m_pose = m_prevPose = m_set;  // before any step: the pose from now on
}

double RigidTool::distanceWorld(size_t i, const Vec3& x, Vec3& normalWorld) {
    const Vec3 local = m_pose.orientation.conjugate() * (x - m_pose.position);
    if (i < m_memo.size()) {
        DistanceMemo& m = m_memo[i];
        if (!(m.valid && std::memcmp(m.local.data(), local.data(), 3 * sizeof(double)) == 0)) {
            m.local = local;
            m.distance = signedDistance(local, m.normal);
            m.valid = true;
        }
        normalWorld = m_pose.orientation * m.normal;
        return m.distance;
    }
    Vec3 nl;
    const double d = signedDistance(local, nl);
    normalWorld = m_pose.orientation * nl;
    return d;
}

void RigidTool::candidates(const core::BaseMechanicalState& s, std::vector<int>& out) const {
    out.clear();
    Vec3 lo, hi;
    if (!localBounds(m_tolerance, lo, hi)) {
        out = m_surface;
        return;
    }
    // the world axis-aligned box around the tool's box (centre +- |rotation| half-extents): most
    // surface nodes are outside it, and three pairs of comparisons reject them without a rotation
    const Mat3 rot = m_pose.orientation.toRotationMatrix(), inv = rot.transpose();
    const Vec3 centre = m_pose.position + rot * (0.5 * (lo + hi)), half = rot.cwiseAbs() * (0.5 * (hi - lo));
    const Vec3 wlo = centre - half, whi = centre + half;
    const Positions& x = s.x();
    for (int i : m_surface) {
        const Vec3& p = x[size_t(i)];
        if (p[0] < wlo[0] || p[0] > whi[0] || p[1] < wlo[1] || p[1] > whi[1] || p[2] < wlo[2] || p[2] > whi[2]) continue;
        const Vec3 l = inv * (p - m_pose.position);
        if ((l.array() >= lo.array()).all() && (l.array() <= hi.array()).all()) out.push_back(i);
    }
}

Vec3 RigidTool::toolVelocity(const Vec3& x) const {
    const double dt = m_poseTime - m_prevTime;
    if (!(dt > 0)) return Vec3::Zero();
    // the tool point at x now was at xo one pose earlier
    const Vec3 xo = m_prevPose.position + m_prevPose.orientation * (m_pose.orientation.conjugate() * (x - m_pose.position));
    return (x - xo) / dt;
}

void RigidTool::projectForces(core::BaseMechanicalState& s) {
    if (&s != m_body || m_contact.size() != s.size()) return;
    Positions& f = s.f();
    Positions& r = s.reaction();
    const Positions& x = s.x();
    const Positions& v = s.v();
    for (int i : m_active) {
        m_contact[size_t(i)] = Vec3::Zero();
        m_slip[size_t(i)] = 0;
        if (size_t(i) < r.size()) r[size_t(i)] = Vec3::Zero();
    }
    m_active.clear();
    m_force = m_torque = Vec3::Zero();
    const bool friction = m_muS > 0 || m_muK > 0;
    const double dt = m_poseTime - m_prevTime;
    const double restSpeed = dt > 0 ? m_tolerance / dt : 0.0;  // slower than the tolerance per step: at rest
    candidates(s, m_scratch);
    for (int k : m_scratch) {
        const size_t i = size_t(k);
        m_slip[i] = 0;
        Vec3 n;
        if (distanceWorld(i, x[i], n) > m_tolerance) continue;
        const double fn = f[i].dot(n);
        if (!(fn < 0)) continue;  // pulled off the tool, or no force: no contact force
        const double N = -fn;
        Vec3 c = N * n;  // removes the push into the tool
        if (friction) {
            const Vec3 ft = f[i] - fn * n;
            Vec3 vt = v[i] - toolVelocity(x[i]);
            vt -= vt.dot(n) * n;
            const double speed = vt.norm(), ftn = ft.norm();
            if (speed <= restSpeed && ftn <= m_muS * N) {
                c -= ft;  // sticks: the tangential force is held
                m_slip[i] = 1;
                m_anchor[i] = m_pose.orientation.conjugate() * (x[i] - m_pose.position);
            } else {
                const Vec3 dir = speed > restSpeed ? Vec3(vt / speed) : ftn > 0 ? Vec3(ft / ftn) : Vec3::Zero();
                c -= m_muK * N * dir;  // slides: kinetic friction against the motion
                m_slip[i] = 2;
                m_slipDir[i] = dir;
            }
        }
        f[i] += c;
        m_contact[i] = c;
        if (i < r.size()) r[i] = c;
        m_active.push_back(k);
        m_force -= c;
        m_torque -= (x[i] - m_pose.position).cross(c);
    }
}

void RigidTool::projectPositions(core::BaseMechanicalState& s, double t) {
    if (&s != m_body) return;
    if (t != m_poseTime) {  // a new time: the pose moves on (a static solver projects at one time often)
        m_prevPose = m_pose;
        m_prevTime = m_poseTime;
        m_pose = m_hasSet ? m_set : m_motion.at(t);
        m_poseTime = t;
    }
    const std::vector<double>* mass = groupMass();
    const double dt = m_poseTime - m_prevTime;
    const double perDt2 = dt > 0 ? 1.0 / (dt * dt) : 0.0;
    Positions& x = s.x();
    Positions& r = s.reaction();
    candidates(s, m_scratch);
    for (int k : m_scratch) {
        const size_t i = size_t(k);
        Vec3 n;
        const double d = distanceWorld(i, x[i], n);
        Vec3 dx = Vec3::Zero();
        if (m_slip[i] == 1) {
            // a sticking node stays on its point of the tool: it moves with the tool over the step
            // whatever else the integrator did to it (mass damping, say, slows it against the tool)
            const Vec3 slide = m_pose.position + m_pose.orientation * m_anchor[i] - x[i];
            dx = slide - slide.dot(n) * n;
        }
        if (d < 0) dx -= d * n;  // onto the closest surface point
        if (dx.isZero()) continue;
        x[i] += dx;
        // the force that gives this correction over the step, m dx / dt^2 (central difference's
        // update): the impulse of a node that reached the tool during the step
        const double m = mass && i < mass->size() ? (*mass)[i] : 0.0;
        const Vec3 c = (m * perDt2) * dx;
        if (c.isZero()) continue;
        if (m_contact[i].isZero()) m_active.push_back(k);
        m_contact[i] += c;
        if (i < r.size()) r[i] += c;
        m_force -= c;
        m_torque -= (x[i] - m_pose.position).cross(c);
    }
}

const std::vector<double>* RigidTool::groupMass() const {
    if (auto* groups = node()->context().groups)
        for (const core::MechanicalGroup& g : *groups)
            if (g.state == m_body) return &g.mass;
    return nullptr;
}

void RigidTool::projectVelocities(core::BaseMechanicalState& s, double t) {
    if (&s != m_body) return;
    Positions& x = s.x();
    Positions& v = s.v();
    for (int k : m_scratch) {  // the candidates of projectPositions, at this pose
        const size_t i = size_t(k);
        Vec3 n;
        if (distanceWorld(i, x[i], n) > m_tolerance) continue;
        const Vec3 vrel = v[i] - toolVelocity(x[i]);
        const double vn = vrel.dot(n);
        if (vn < 0) v[i] -= vn * n;  // no approach into the tool
        const Vec3 vt = vrel - vn * n;
        if (m_slip[i] == 1 || (m_slip[i] == 2 && vt.dot(m_slipDir[i]) < 0)) v[i] -= vt;  // sticks, or stopped
    }
}

} // namespace fascia::contact
