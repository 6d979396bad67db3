#include "fascia/haptics/VirtualCoupling.h"
#include "fascia/base/StateIO.h"

#include <cmath>
#include <stdexcept>

namespace fascia::haptics {

VirtualCoupling::VirtualCoupling(double stiffness, double damping, double filterTime)
    : m_k(stiffness), m_c(damping), m_filterTime(filterTime) {
    if (!(std::isfinite(filterTime) && filterTime >= 0))
        throw std::invalid_argument("VirtualCoupling: the filter time must be a non-negative number of seconds");
    if (!(std::isfinite(stiffness) && stiffness > 0))
        throw std::invalid_argument("VirtualCoupling: the stiffness must be a positive number of N/m");
    if (!(std::isfinite(damping) && damping >= 0))
        throw std::invalid_argument("VirtualCoupling: the damping must be a non-negative number of N s/m");
}

Vec3 VirtualCoupling::proxy(const Vec3& xDevice, const Vec3& contact, double dt) {
    m_filtered += dt / (m_filterTime + dt) * (contact - m_filtered);
    return toolTarget(xDevice, m_filtered);
}

void VirtualCoupling::publishDevice(const Vec3& x, const Vec3& v) {
    std::lock_guard<std::mutex> lock(m_deviceMutex);
    m_device.position = x;
    m_device.velocity = v;
    ++m_device.sequence;
}

void VirtualCoupling::publishTool(const Vec3& x, const Vec3& v, const Vec3& contact) {
    std::lock_guard<std::mutex> lock(m_toolMutex);
    m_tool.position = x;
    m_tool.velocity = v;
    m_tool.force = contact;
    ++m_tool.sequence;
}

CouplingSample VirtualCoupling::device() const {
    std::lock_guard<std::mutex> lock(m_deviceMutex);
    return m_device;
}

CouplingSample VirtualCoupling::tool() const {
    std::lock_guard<std::mutex> lock(m_toolMutex);
    return m_tool;
}

Vec3 VirtualCoupling::forceFelt(const Vec3& x, const Vec3& v, std::uint64_t* sequence) const {
    const CouplingSample t = tool();
    if (sequence) *sequence = t.sequence;
    if (t.sequence == 0) return Vec3::Zero();
    return force(x, v, t.position, t.velocity);
}

namespace {
void putSample(core::StateWriter& out, const std::string& side, const CouplingSample& s) {
    out.put(side + ".position", s.position.data(), 3);
    out.put(side + ".velocity", s.velocity.data(), 3);
    out.put(side + ".force", s.force.data(), 3);
    out.put(side + ".sequence", long(s.sequence));
}
CouplingSample getSample(core::StateReader& in, const std::string& side) {
    CouplingSample s;
    in.getInto(side + ".position", s.position.data(), 3);
    in.getInto(side + ".velocity", s.velocity.data(), 3);
    in.getInto(side + ".force", s.force.data(), 3);
    s.sequence = std::uint64_t(in.getLong(side + ".sequence"));
    return s;
}
} // namespace

void VirtualCoupling::saveState(core::StateWriter& out) const {
    out.put("filtered", m_filtered.data(), 3);
    putSample(out, "device", device());
    putSample(out, "tool", tool());
}

void VirtualCoupling::restoreState(core::StateReader& in) {
    in.getInto("filtered", m_filtered.data(), 3);
    const CouplingSample d = getSample(in, "device"), t = getSample(in, "tool");
    {
        std::lock_guard<std::mutex> lock(m_deviceMutex);
        m_device = d;
    }
    std::lock_guard<std::mutex> lock(m_toolMutex);
    m_tool = t;
}

} // namespace fascia::haptics
