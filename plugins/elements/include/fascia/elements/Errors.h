#pragma once
/// One error style for the element force fields: input errors through Component::fail() (located
/// "file:line: error: Type 'name': message"), run-time errors through runtimeError() in the core's
/// run-time style ("[path] message", as core::Simulation's own run-time errors).
#include "fascia/base/Component.h"

#include <string>

namespace fascia::elements {

/// Throws a simulation (run-time) error "[path] message" for `owner`.
[[noreturn]] void runtimeError(const core::Component& owner, const std::string& message);

} // namespace fascia::elements
