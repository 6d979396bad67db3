#pragma once
/// Located errors in compiler format ("file:line: error: message"), so editors jump to the spot.
#include <stdexcept>
#include <string>
#include <vector>

namespace fascia::core {

/// A place in an input file. line 0 means "the whole file"; an empty file means "no file". A
/// binary file has no lines: its places are byte offsets (byte >= 0; line is then 0).
struct SourceLoc {
    std::string file;
    int line = 0;
    long long byte = -1;
    bool empty() const { return file.empty(); }
    std::string str() const;   ///< "file:line", "file: byte N", "file" or ""
};

/// What kind of failure; fascia-run maps it to its exit code.
enum class ErrorKind {
    Input,        ///< invalid scene, mesh or value: exit code 2
    Simulation,   ///< NaN or instability while running: exit code 3
    Internal,     ///< anything else: exit code 1
    Output        ///< an output file or folder that cannot be written: exit code 1
};

/// The one exception type of Fascia. what() is the whole formatted message, notes included.
class Error : public std::runtime_error {
public:
    Error(ErrorKind kind, SourceLoc loc, std::string message, std::vector<std::string> notes = {});
    ErrorKind kind() const { return m_kind; }
    const SourceLoc& loc() const { return m_loc; }
    const std::string& message() const { return m_message; }
    const std::vector<std::string>& notes() const { return m_notes; }

    /// Formats "file:line: error: message\nfile:line: note: n1\n..." ("file: byte N: error: ..." at a
    /// byte offset).
    static std::string format(const SourceLoc& loc, const std::string& message,
                              const std::vector<std::string>& notes);

private:
    ErrorKind m_kind;
    SourceLoc m_loc;
    std::string m_message;
    std::vector<std::string> m_notes;
};

/// Invalid input (scene, mesh, parameter value) located at loc: exit code 2.
[[noreturn]] void throwInputError(const SourceLoc& loc, const std::string& message,
                                  std::vector<std::string> notes = {});
/// An output that cannot be written (a folder that is a file, no permission): exit code 1.
[[noreturn]] void throwOutputError(const SourceLoc& loc, const std::string& message,
                                   std::vector<std::string> notes = {});
/// The simulation failed while running (NaN, instability): exit code 3.
[[noreturn]] void throwSimulationError(const std::string& message);

/// Levenshtein distance, for "did you mean" suggestions.
int editDistance(const std::string& a, const std::string& b);
/// Up to max candidates close to word (case-insensitive), best first.
std::vector<std::string> closestMatches(const std::string& word, const std::vector<std::string>& candidates,
                                        size_t max = 3);

} // namespace fascia::core
