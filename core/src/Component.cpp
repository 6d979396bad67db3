#include "fascia/base/Component.h"
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

#include <chrono>
#include <cxxabi.h>
#include <cstdlib>
#include <iostream>

namespace fascia::core {

namespace {
bool g_timers = false;
TimerClock g_timerClock = nullptr;
}
void setTimersEnabled(bool on) { g_timers = on; }
bool timersEnabled() { return g_timers; }
void setTimerClock(TimerClock clock) { g_timerClock = clock; }
double timerNow() {
    if (g_timerClock) return g_timerClock();
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Base::Base() = default;

BaseParam* Base::findParam(const std::string& name) const {
    for (auto* p : m_params)
        if (p->name() == name) {
            // a lookup by name is how a link or a test reads an output (ParamLog.h)
            if (paramLogEnabled()) paramLogRecord(*p, "lookup");
            return p;
        }
    return nullptr;
}

std::vector<std::string> Base::paramNames() const {
    std::vector<std::string> out;
    for (auto* p : m_params) out.push_back(p->name());
    return out;
}

namespace {
std::string who(const Base& b) {
    std::string s = b.className().empty() ? std::string("object") : b.className();
    if (!b.name().empty()) s += " '" + b.name() + "'";
    return s;
}
} // namespace

void Base::fail(const std::string& message, std::vector<std::string> notes) const {
    throwInputError(m_loc, who(*this) + ": " + message, std::move(notes));
}

void Base::fail(const BaseParam& p, const std::string& message, std::vector<std::string> notes) const {
    throwInputError(p.loc().empty() ? m_loc : p.loc(), who(*this) + ": " + message, std::move(notes));
}

void Base::failOutput(const BaseParam* p, const std::string& message, std::vector<std::string> notes) const {
    throwOutputError(p && p->isSet() && !p->loc().empty() ? p->loc() : m_loc, who(*this) + ": " + message, std::move(notes));
}

void Base::warn(const std::string& message) const {
    const std::string where = m_loc.empty() ? std::string() : m_loc.str() + ": ";
    std::cerr << where << "warning: " << who(*this) << ": " << message << "\n";
}

std::string Component::path() const {
    std::string p = m_node ? m_node->path() : std::string();
    if (p != "/") p += "/";
    return p + name();
}

std::vector<Component*> Component::dependencies() const {
    std::vector<Component*> out;
    if (!m_node) return out;
    if (auto* t = m_node->findInContext<BaseTopology>(); t && t != this) out.push_back(t);
    if (auto* s = m_node->findInContext<BaseMechanicalState>(); s && s != this) out.push_back(s);
    return out;
}

void BaseLink::parseValue(const std::string& text, const SourceLoc&) {
    // read() keeps "@..." texts as links; anything else would be silently ignored
    if (!text.empty())
        m_owner->fail(*this, name() + " = \"" + text + "\" is not a link: write \"@" + text + "\"");
    m_path = text;
}

std::string demangledTypeName(const char* mangled) {
    int status = 0;
    char* d = abi::__cxa_demangle(mangled, nullptr, nullptr, &status);
    std::string s = (status == 0 && d) ? d : mangled;
    std::free(d);
    const auto colon = s.rfind("::");
    return colon == std::string::npos ? s : s.substr(colon + 2);
}

} // namespace fascia::core
