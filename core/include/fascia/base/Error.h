#pragma once
/// Located errors in compiler format ("file:line: error: message"), so editors jump to the spot.
#include <cstddef>
#include <memory>
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
///
/// One Error may stand for several: a scene reports every independent mistake it finds in one load
/// (core::ErrorList, docs/design.md section 7). kind(), loc(), message() and notes() are then the
/// first error's, more() holds the others in order, and what() is the first error's text with each
/// other's on the lines after it, then "file: note: N more errors not shown" past the limit, so that
/// any catch site that prints what() prints them all.
class Error : public std::runtime_error {
public:
    Error(ErrorKind kind, SourceLoc loc, std::string message, std::vector<std::string> notes = {});
    /// first standing for the errors found with it: more (single errors, in order) and `unshown` more
    /// that were counted but not kept; `where` (the scene) locates the line about those.
    Error(const Error& first, std::vector<Error> more, size_t unshown, const SourceLoc& where);
    ErrorKind kind() const { return m_kind; }
    const SourceLoc& loc() const { return m_loc; }
    const std::string& message() const { return m_message; }
    const std::vector<std::string>& notes() const { return m_notes; }
    /// The further errors this one stands for (empty for a single error), each without more of its own.
    const std::vector<Error>& more() const;
    /// Errors found past the limit, counted but not kept.
    size_t unshown() const { return m_unshown; }
    /// How many errors this one stands for: 1 + more().size() + unshown().
    size_t count() const { return 1 + more().size() + m_unshown; }

    /// Formats "file:line: error: message\nfile:line: note: n1\n..." ("file: byte N: error: ..." at a
    /// byte offset).
    static std::string format(const SourceLoc& loc, const std::string& message,
                              const std::vector<std::string>& notes);

private:
    ErrorKind m_kind;
    SourceLoc m_loc;
    std::string m_message;
    std::vector<std::string> m_notes;
    // shared, so that copying an exception (which every throw and catch by value does) stays cheap
    std::shared_ptr<const std::vector<Error>> m_more;
    size_t m_unshown = 0;
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
