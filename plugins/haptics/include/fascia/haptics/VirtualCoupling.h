#pragma once
/// Virtual coupling for haptic force feedback: a device proxy joined to a simulated rigid tool by a
/// spring-damper, so that a 1 kHz device loop gets a smooth, stable force while the simulation steps
/// at its own rate (J. E. Colgate, M. C. Stanley and J. M. Brown, "Issues in the haptic display of
/// tool use", IROS 1995). For embedding programs: no scene component, no plugin header needed.
///
/// Two threads share one VirtualCoupling:
/// - the device thread, at 1 kHz: publishDevice(x_d, v_d), then forceFelt(x_d, v_d), which reads the
///   latest tool state the simulation published: F = -k (x_d - x_t) - c (v_d - v_t);
/// - the simulation thread, once per step: device() for the latest device sample, toolTarget() for
///   where to put the tool (Simulation::tool(...).setPose), sim->step(), then publishTool(x_t, v_t,
///   F_contact) with the tool's pose and the force the body exerted on it (BaseTool::force()).
/// Each side copies a few numbers under a mutex held for nothing else, so neither ever waits on the
/// other's work: the device thread never waits for a step.
#include "fascia/base/Types.h"

#include <cstdint>
#include <mutex>

namespace fascia::core {
class StateWriter;
class StateReader;
} // namespace fascia::core

namespace fascia::haptics {

/// What one side publishes: a position, a velocity and (tool side) the contact force, with a
/// counter that says how many samples were published before it.
struct CouplingSample {
    Vec3 position = Vec3::Zero();  ///< m
    Vec3 velocity = Vec3::Zero();  ///< m/s
    Vec3 force = Vec3::Zero();     ///< N: the force the body exerts on the tool (tool side only)
    std::uint64_t sequence = 0;    ///< 0: nothing published yet; then 1, 2 ...
};

class VirtualCoupling {
public:
    /// stiffness k (N/m, > 0) and damping c (N s/m, >= 0) of the spring-damper, and the time
    /// constant (s, >= 0) of the low-pass filter proxy() puts on the contact force; throws
    /// std::invalid_argument otherwise.
    VirtualCoupling(double stiffness, double damping, double filterTime = 0.005);

    double stiffness() const { return m_k; }
    double damping() const { return m_c; }

    /// The spring-damper force felt at the device: -k (x_d - x_t) - c (v_d - v_t) (N).
    Vec3 force(const Vec3& xDevice, const Vec3& vDevice, const Vec3& xTool, const Vec3& vTool) const {
        return -m_k * (xDevice - xTool) - m_c * (vDevice - vTool);
    }
    /// Where the simulation puts the tool for a device at xDevice while the body pushes on it with
    /// `contact` (N): the proxy position at which the spring balances the contact force,
    /// k (x_d - x_t) + F_contact = 0, i.e. x_t = x_d + F_contact / k. Off contact the tool follows the
    /// device; in contact it stays outside the tissue by the spring's stretch.
    Vec3 toolTarget(const Vec3& xDevice, const Vec3& contact) const { return xDevice + contact / m_k; }
    /// Simulation thread, once per step of dt: toolTarget for the contact force low-passed with the
    /// filter time T, F_f += dt / (T + dt) (F - F_f). Kinematic contact (the tool's pose imposed, the
    /// penetrating nodes projected out) gives an impulsive force on the step a node is pushed out;
    /// fed back unfiltered, it throws the tool out and back by F / k from one step to the next.
    Vec3 proxy(const Vec3& xDevice, const Vec3& contact, double dt);
    /// The filtered contact force proxy() last used (N).
    const Vec3& filteredContact() const { return m_filtered; }

    /// Device thread: the device's position and velocity.
    void publishDevice(const Vec3& x, const Vec3& v);
    /// Simulation thread: the tool's position and velocity after a step, and the body's force on it.
    void publishTool(const Vec3& x, const Vec3& v, const Vec3& contact);
    /// The latest samples (copies).
    CouplingSample device() const;
    CouplingSample tool() const;
    /// Device thread: the force felt for the device at (x, v) against the latest tool sample (zero
    /// before the simulation published one), and that sample's sequence number in `sequence`.
    Vec3 forceFelt(const Vec3& x, const Vec3& v, std::uint64_t* sequence = nullptr) const;

    /// What the coupling carries from one step to the next, as checkpoint records
    /// (fascia/base/StateIO.h): proxy()'s filtered contact force and the latest sample of each side.
    /// It is no scene component, so Simulation::save does not hold it: an embedding program that
    /// checkpoints its simulation writes these records beside it, and restoreState() (on a coupling of
    /// the same stiffness, damping and filter time) continues bitwise; a record of the wrong name or
    /// size is an error of the reader.
    void saveState(core::StateWriter& out) const;
    void restoreState(core::StateReader& in);

private:
    double m_k, m_c, m_filterTime;
    Vec3 m_filtered = Vec3::Zero();  // proxy()'s state: the simulation thread's own
    mutable std::mutex m_deviceMutex, m_toolMutex;  // each held only to copy one sample
    CouplingSample m_device, m_tool;
};

} // namespace fascia::haptics
