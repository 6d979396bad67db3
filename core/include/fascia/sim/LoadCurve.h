#pragma once
/// Load curves: one facility for every time-dependent input. A load scales its full value by a
/// curve, F(t) = c(t) F (ConstantForce, the root node's gravity, SurfacePressure,
/// PrescribedDisplacement, and any later load or solver that samples it at its load steps).
///
/// A curve is a table of points (t_k, c_k), times non-decreasing, interpolated linearly or smoothly
/// between them, with the first value held before the first point and the last value held after the
/// last point ("hold") or the last segment continued ("extend", linear interpolation only). Two
/// points at one time make a jump: the curve takes the first value up to that time and the second
/// after it.
///   linear:  c(t) = c_k + (c_(k+1) - c_k) r,             r = (t - t_k) / (t_(k+1) - t_k)
///   smooth:  c(t) = c_k + (c_(k+1) - c_k) s(r),          s(r) = r^3 (10 - 15 r + 6 r^2)
/// (s is the 3-4-5 polynomial: s(0) = 0, s(1) = 1, s' and s'' zero at both ends).
///
/// In a scene a curve is a `<LoadCurve>` component (mechanics plugin) linked as curve="@name", or
/// written inline on the load (the `curve` parameter's inline forms):
///   "ramp T"            0 at t = 0 to 1 at t = T, linearly, then held
///   "smoothStep T"      the same with the smooth polynomial
///   "step t0"           0 up to t0, 1 after it
///   "linear t1 c1 t2 c2 ..."   tabulated points, linear interpolation, last value held
///   "smooth t1 c1 t2 c2 ..."   tabulated points, smooth interpolation, last value held
/// any of which may end with the word "extend" (continue the last segment; linear forms only).
#include "fascia/base/Component.h"

#include <string>
#include <vector>

namespace fascia::core {

class Curve {
public:
    enum class Interpolation { Linear, Smooth };
    enum class After { Hold, Extend };

    /// The constant curve c(t) = 1 (a load without a curve).
    Curve() : m_t{0.0}, m_c{1.0} {}
    /// From points t1 c1 t2 c2 ...; returns the problem ("" when fine): no points, an odd count,
    /// times that decrease, a non-finite number, extend with smooth interpolation.
    static std::string make(const std::vector<double>& points, Interpolation interp, After after, Curve& out);
    /// Parses an inline form (see the file comment); returns the problem ("" when fine).
    static std::string parse(const std::string& text, Curve& out);

    /// c(t).
    double value(double t) const;
    /// dc/dt, from the right (0 up to the first point: a load starts at rest).
    double rate(double t) const;

    const std::vector<double>& times() const { return m_t; }
    const std::vector<double>& values() const { return m_c; }
    Interpolation interpolation() const { return m_interp; }
    After after() const { return m_after; }
    /// The points as "t1 c1 t2 c2 ..." plus the interpolation (for messages and --describe).
    std::string text() const;

private:
    std::vector<double> m_t, m_c;
    Interpolation m_interp = Interpolation::Linear;
    After m_after = After::Hold;
};

/// A component that offers a curve (the mechanics plugin's LoadCurve), for curve="@name" links.
class BaseLoadCurve : public Component {
public:
    virtual const Curve& curve() const = 0;
    std::vector<Component*> dependencies() const override { return {}; }
};

/// The `curve` parameter of a load: a link to a LoadCurve ("@ramp") or an inline form ("ramp 0.5").
/// Unset, the curve is 1 at all times.
class CurveParam : public BaseLink {
public:
    CurveParam(Base* owner, ParamSpec spec) : BaseLink(owner, std::move(spec)) {}
    /// The curve: the linked component's, the inline one, or the constant 1.
    const Curve& get() const { return m_target ? m_target->curve() : m_inline; }
    double value(double t) const { return get().value(t); }
    double rate(double t) const { return get().rate(t); }
    /// Sets an inline curve from code.
    void set(const Curve& c) { m_inline = c; m_target = nullptr; markSet(); }

    std::string typeName() const override { return "load curve"; }
    std::string valueText() const override { return m_target || !m_link.empty() ? m_link : m_text; }
    bool setTarget(Component* c) override {
        m_target = dynamic_cast<BaseLoadCurve*>(c);
        if (m_target) markSet();
        return m_target != nullptr;
    }
    Component* targetComponent() const override { return m_target; }
    std::string targetType() const override { return "LoadCurve"; }

protected:
    void parseValue(const std::string& text, const SourceLoc& loc) override;

private:
    BaseLoadCurve* m_target = nullptr;
    Curve m_inline;
    std::string m_text;
};

/// The curve parameter's declaration with its help text (the inline forms), for every load.
ParamSpec curveSpec(const char* name, const std::string& what);

} // namespace fascia::core
