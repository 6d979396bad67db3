#pragma once
/// What every fuzz target in tests/fuzz/ shares (docs/robustness.md says how to run them).
///
/// A target is one LLVMFuzzerTestOneInput. Built with FASCIA_FUZZ=ON (clang) it links libFuzzer;
/// in the normal build it links ReplayMain.cpp instead, which feeds it every file of its seed corpus
/// and of its regression inputs (the fuzz_inputs_* ctest entries). The readers take paths, so each
/// input is written to a scratch folder of the process first.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace fascia::fuzz {

/// This process's scratch folder: made on first use under the system temporary folder, removed at
/// exit.
const std::string& scratchDir();

/// Writes size bytes to scratchDir()/name (replacing what was there) and returns its path.
std::string writeScratch(const std::string& name, const uint8_t* data, size_t size);
std::string writeScratch(const std::string& name, const std::string& bytes);
/// Removes scratchDir()/name when it exists.
void removeScratch(const std::string& name);

/// Runs f on one input. A fascia::core::Error of kind Input or Output that names a file is the normal
/// outcome of a bad input. Anything else is a finding: another exception escaping, or a fascia error
/// without a location (or of kind Internal or Simulation); it is printed with the target's name,
/// then the process aborts, which libFuzzer records as a crash and the replay run as a failure.
/// Crashes, undefined behaviour, leaks, timeouts and huge allocations are caught by the sanitizers
/// and by libFuzzer's -timeout and -rss_limit_mb / -malloc_limit_mb. With the environment variable
/// FASCIA_FUZZ_VERBOSE set, each outcome is printed ("accepted" or the error), to check seeds.
void runExpectingLocatedErrors(const char* target, const std::function<void()>& f);

} // namespace fascia::fuzz
