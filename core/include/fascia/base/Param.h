#pragma once
/// Typed parameters declared once: name, type, default, unit, range or choices, required, help.
/// The one declaration drives XML parsing, validation, error messages and `fascia-run --describe`.
#include "fascia/base/Error.h"
#include "fascia/base/ParamLog.h"
#include "fascia/base/Types.h"

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fascia::core {

class Base;

/// The declaration of a parameter, built with chained setters:
/// `ParamSpec("youngModulus").unit("Pa").above(0).help("Young's modulus E")`.
struct ParamSpec {
    explicit ParamSpec(std::string n) : name(std::move(n)) {}
    ParamSpec& unit(std::string u) { unitText = std::move(u); return *this; }
    ParamSpec& help(std::string h) { helpText = std::move(h); return *this; }
    ParamSpec& required() { isRequired = true; return *this; }
    /// Values (each element for lists and vectors) must be >= v (> v when exclusive).
    ParamSpec& min(double v, bool exclusive = false) { lo = v; loExclusive = exclusive; return *this; }
    ParamSpec& max(double v, bool exclusive = false) { hi = v; hiExclusive = exclusive; return *this; }
    ParamSpec& above(double v) { return min(v, true); }
    ParamSpec& below(double v) { return max(v, true); }
    ParamSpec& choices(std::vector<std::string> c) { choiceList = std::move(c); return *this; }
    /// A value computed by the component (positions of a loader...): linkable, not settable in XML.
    ParamSpec& output() { isOutput = true; return *this; }
    /// Number of entries a list must have (e.g. 6 for a box "xmin ymin zmin xmax ymax zmax").
    ParamSpec& count(size_t n) { fixedCount = n; return *this; }

    std::string name, unitText, helpText;
    bool isRequired = false, isOutput = false;
    std::optional<double> lo, hi;
    bool loExclusive = false, hiExclusive = false;
    std::vector<std::string> choiceList;
    std::optional<size_t> fixedCount;

    std::string rangeText() const;  ///< "[0, 0.5)", "> 0", "one of a|b|c", "" if unconstrained
};

/// Type-erased parameter, owned by a Base (component or node).
class BaseParam {
public:
    BaseParam(Base* owner, ParamSpec spec);
    virtual ~BaseParam() = default;
    BaseParam(const BaseParam&) = delete;
    BaseParam& operator=(const BaseParam&) = delete;

    const ParamSpec& spec() const { return m_spec; }
    const std::string& name() const { return m_spec.name; }
    Base* owner() const { return m_owner; }
    virtual std::string typeName() const = 0;
    virtual std::string defaultText() const = 0;
    virtual std::string valueText() const = 0;

    /// Parses an XML attribute string; a bad value is a located input error.
    void read(const std::string& text, const SourceLoc& loc);
    /// True once set from the scene (a value or a link) or from code.
    bool isSet() const { return m_set; }
    const SourceLoc& loc() const { return m_loc; }

    /// "@path" or "@path.field": the link text, empty when the value is literal.
    const std::string& linkText() const { return m_link; }
    /// True when this parameter's type can take a value from another parameter (by "@comp.field").
    virtual bool canBindTo(const BaseParam& source) const = 0;
    /// Makes this parameter read its value from source (same type), resolved at init.
    virtual void bindTo(const BaseParam* source) = 0;
    virtual bool isComponentLink() const { return false; }
    /// The component a link resolved to (set by the scene builder), for the init order.
    Base* linkTarget() const { return m_linkTarget; }
    void setLinkTarget(Base* b) { m_linkTarget = b; }

    /// Checks the current value against range/choices; throws a located error naming the owner.
    void checkValue() const;

protected:
    virtual void parseValue(const std::string& text, const SourceLoc& loc) = 0;
    /// Range check of the stored value; returns an empty string when fine, else the problem.
    virtual std::string rangeProblem() const = 0;
    /// Marks the parameter set; while the coverage log is on (ParamLog.h) it records the set.
    void markSet() {
        m_set = true;
        if (paramLogEnabled()) paramLogRecord(*this, "set");
    }
    [[noreturn]] void badValue(const std::string& text, const std::string& expected, const SourceLoc& loc) const;
    friend class Base;

    Base* m_owner;
    ParamSpec m_spec;
    bool m_set = false;
    SourceLoc m_loc;
    std::string m_link;
    Base* m_linkTarget = nullptr;
};

/// Parsing and printing for each parameter value type.
template <class T> struct ParamTraits;  // specialised in Param.cpp for the supported types

#define FASCIA_DECLARE_PARAM_TRAITS(T)                                               \
    template <> struct ParamTraits<T> {                                              \
        static const char* typeName();                                               \
        static bool parse(const std::string& text, T& out, std::string& expected);   \
        static std::string format(const T& v);                                       \
        static std::string check(const T& v, const ParamSpec& spec);                 \
    };
FASCIA_DECLARE_PARAM_TRAITS(bool)
FASCIA_DECLARE_PARAM_TRAITS(int)
FASCIA_DECLARE_PARAM_TRAITS(double)
FASCIA_DECLARE_PARAM_TRAITS(std::string)
FASCIA_DECLARE_PARAM_TRAITS(Vec3)
FASCIA_DECLARE_PARAM_TRAITS(IndexList)
FASCIA_DECLARE_PARAM_TRAITS(NumberList)
FASCIA_DECLARE_PARAM_TRAITS(FilePath)
FASCIA_DECLARE_PARAM_TRAITS(TimeStep)
FASCIA_DECLARE_PARAM_TRAITS(Positions)
FASCIA_DECLARE_PARAM_TRAITS(Tetrahedra)
FASCIA_DECLARE_PARAM_TRAITS(Hexahedra)
FASCIA_DECLARE_PARAM_TRAITS(Triangles)
FASCIA_DECLARE_PARAM_TRAITS(MeshData)
#undef FASCIA_DECLARE_PARAM_TRAITS

/// Value-initialised default of a parameter type (zero for vectors, which Eigen leaves undefined).
template <class T> T zeroValue() {
    if constexpr (std::is_same_v<T, Vec3>) return Vec3::Zero();
    else return T{};
}

/// A typed parameter. Read with get() (follows a link), write with set().
template <class T>
class Param : public BaseParam {
public:
    Param(Base* owner, ParamSpec spec, T defaultValue = zeroValue<T>())
        : BaseParam(owner, std::move(spec)), m_value(defaultValue), m_default(std::move(defaultValue)) {}

    const T& get() const { return m_source ? m_source->get() : m_view ? *m_view : m_value; }
    const T& operator*() const { return get(); }
    const T* operator->() const { return &get(); }
    /// Sets the value from code (a component filling its outputs, or an embedding program).
    void set(T v) { m_value = std::move(v); m_source = nullptr; m_view = nullptr; markSet(); }
    /// Direct write access for outputs filled in place.
    T& edit() { m_source = nullptr; m_view = nullptr; markSet(); return m_value; }
    /// Makes an output read its value from an object its component keeps elsewhere, without a copy
    /// (a mesh source's "tetrahedra" is the tetrahedra of its "mesh"): get() returns *v until the
    /// next set() or edit(). v must outlive the parameter.
    void view(const T* v) { m_value = zeroValue<T>(); m_source = nullptr; m_view = v; markSet(); }

    std::string typeName() const override { return ParamTraits<T>::typeName(); }
    std::string defaultText() const override { return ParamTraits<T>::format(m_default); }
    std::string valueText() const override { return ParamTraits<T>::format(get()); }
    bool canBindTo(const BaseParam& source) const override {
        return dynamic_cast<const Param<T>*>(&source) != nullptr;
    }
    void bindTo(const BaseParam* source) override {
        m_source = dynamic_cast<const Param<T>*>(source);
        markSet();
    }

protected:
    void parseValue(const std::string& text, const SourceLoc& loc) override {
        std::string expected;
        T v = zeroValue<T>();
        if constexpr (std::is_same_v<T, FilePath>) {
            if (!ParamTraits<T>::parse(text, v, expected)) badValue(text, expected, loc);
            v.resolved = resolvePath(text, loc);
        } else {
            if (!ParamTraits<T>::parse(text, v, expected)) badValue(text, expected, loc);
        }
        m_value = std::move(v);
        m_source = nullptr;
        m_view = nullptr;
    }
    std::string rangeProblem() const override { return ParamTraits<T>::check(get(), m_spec); }

private:
    static std::string resolvePath(const std::string& text, const SourceLoc& loc);
    T m_value;
    T m_default;
    const Param<T>* m_source = nullptr;
    const T* m_view = nullptr;  ///< view(): the value kept elsewhere
};

/// Resolves a path written in a scene relative to the scene file's folder.
std::string resolveScenePath(const std::string& text, const SourceLoc& loc);
template <class T>
std::string Param<T>::resolvePath(const std::string& text, const SourceLoc& loc) {
    return resolveScenePath(text, loc);
}

} // namespace fascia::core
