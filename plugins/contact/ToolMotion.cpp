#include "ToolMotion.h"
#include "fascia/base/Format.h"

#include <cmath>

namespace fascia::contact {

using core::formatNumber;

ToolMotion::ToolMotion(core::Component* owner)
    : position(owner, core::ParamSpec("position").unit("m").help("the tool's reference point in the world frame (fixed pose, or the start of a positionCurve motion)"), Vec3::Zero()),
      orientation(owner, core::ParamSpec("orientation").count(4).help("the tool's orientation as a quaternion w x y z (normalised)"), NumberList{1, 0, 0, 0}),
      displacement(owner, core::ParamSpec("displacement").unit("m").help("with positionCurve: the position is position + c(t) displacement"), Vec3::Zero()),
      positionCurve(owner, core::curveSpec("positionCurve", "the motion: position(t) = position + c(t) displacement")),
      keyTimes(owner, core::ParamSpec("keyTimes").unit("s").help("keyframe times, increasing (with keyPositions and optionally keyOrientations)")),
      keyPositions(owner, core::ParamSpec("keyPositions").unit("m").help("keyframe positions, 3 numbers per key time; linear between keys, the last held")),
      keyOrientations(owner, core::ParamSpec("keyOrientations").help("keyframe orientations, 4 numbers (w x y z) per key time; slerp between keys (default: orientation)")) {}

Eigen::Quaterniond readQuaternion(const core::Component& owner, const core::BaseParam& p, const double* q) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(n > 0) || !std::isfinite(n))
        owner.fail(p, "the quaternion " + formatNumber(q[0], 6) + " " + formatNumber(q[1], 6) + " " + formatNumber(q[2], 6) + " " +
                          formatNumber(q[3], 6) + " has no direction (norm " + formatNumber(n, 6) + ")",
                   {"give w x y z with a non-zero norm, e.g. \"1 0 0 0\" for no rotation"});
    return Eigen::Quaterniond(q[0] / n, q[1] / n, q[2] / n, q[3] / n);
}

void ToolMotion::init(const core::Component& owner) {
    m_orientation = readQuaternion(owner, orientation, orientation.get().data());
    m_keys.clear();
    const NumberList& kt = keyTimes.get();
    const NumberList& kp = keyPositions.get();
    const NumberList& ko = keyOrientations.get();
    const bool keyed = keyTimes.isSet() || keyPositions.isSet() || keyOrientations.isSet();
    if (keyed && positionCurve.isSet())
        owner.fail(positionCurve, "a tool moves by keyframes or by positionCurve, not both");
    if (!keyed) return;
    if (kt.empty()) owner.fail(keyTimes, "keyframes need keyTimes (one time per key)");
    for (size_t k = 1; k < kt.size(); ++k)
        if (!(kt[k] > kt[k - 1]))
            owner.fail(keyTimes, "keyframe times must increase: key " + std::to_string(k) + " (t = " + formatNumber(kt[k], 6) +
                                     " s) does not come after key " + std::to_string(k - 1) + " (t = " + formatNumber(kt[k - 1], 6) + " s)",
                       {"list the keys in time order, each at its own time"});
    if (kp.size() != 3 * kt.size())
        owner.fail(keyPositions, "has " + std::to_string(kp.size()) + " numbers for " + std::to_string(kt.size()) +
                                     " key times: give 3 (x y z) per key");
    if (keyOrientations.isSet() && ko.size() != 4 * kt.size())
        owner.fail(keyOrientations, "has " + std::to_string(ko.size()) + " numbers for " + std::to_string(kt.size()) +
                                        " key times: give 4 (w x y z) per key");
    for (size_t k = 0; k < kt.size(); ++k) {
        core::Pose p;
        p.position = Vec3(kp[3 * k], kp[3 * k + 1], kp[3 * k + 2]);
        p.orientation = keyOrientations.isSet() ? readQuaternion(owner, keyOrientations, ko.data() + 4 * k) : m_orientation;
        m_keys.push_back(p);
    }
}

core::Pose ToolMotion::at(double t) const {
    core::Pose p;
    if (m_keys.empty()) {
        p.position = position.get() + (positionCurve.isSet() ? positionCurve.value(t) : 0.0) * displacement.get();
        p.orientation = m_orientation;
        return p;
    }
    const NumberList& kt = keyTimes.get();
    if (t <= kt.front()) return m_keys.front();
    if (t >= kt.back()) return m_keys.back();
    size_t k = 1;
    while (kt[k] < t) ++k;
    const double r = (t - kt[k - 1]) / (kt[k] - kt[k - 1]);
    p.position = (1 - r) * m_keys[k - 1].position + r * m_keys[k].position;
    p.orientation = m_keys[k - 1].orientation.slerp(r, m_keys[k].orientation);
    return p;
}

} // namespace fascia::contact
