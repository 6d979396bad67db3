#pragma once
/// The parameter-coverage log read by tests/coverage (see tests/coverage/README.md). While the
/// environment variable FASCIA_PARAM_LOG names a file, the core appends one line to it the first
/// time (per process) each parameter of each component type is set (from a scene attribute, a link
/// or code) or looked up by name from outside the scene loader. Off, it costs one test of a flag.
#include <string>

namespace fascia::core {

class BaseParam;

/// True when FASCIA_PARAM_LOG names a file (read once per process).
bool paramLogEnabled();

/// Appends one line to the log, with a single write on a file opened with O_APPEND, so that
/// lines of processes running in parallel never interleave. Does nothing when the log is off.
void paramLogWrite(const std::string& line);

/// Records "kind<TAB>className<TAB>dynamicType<TAB>parameter" once per process for each
/// distinct line. kind is "set" or "lookup". className is empty for a component built in code.
void paramLogRecord(const BaseParam& p, const char* kind);

} // namespace fascia::core
