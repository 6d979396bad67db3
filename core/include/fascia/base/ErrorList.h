#pragma once
/// The errors of one phase of a load, gathered so that a scene reports every independent mistake it
/// can find in one run, as a compiler does, instead of the first one only (docs/design.md, section 7).
#include "fascia/base/Error.h"

#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace fascia::core {

/// The most errors one Error shows: the first and kErrorsShown - 1 more; the others are counted.
constexpr size_t kErrorsShown = 20;

/// Collects located errors with an order key (where their element is in the scene), and throws them
/// together as one Error: the first in order, standing for the others (Error::more).
///
/// ```
/// ErrorList errors({"scene.xml", 0});
/// for (auto& e : elements) errors.attempt(e.index, [&] { check(e); });  // goes on after a failure
/// errors.throwIfAny();                                                  // then stops the load
/// ```
class ErrorList {
public:
    /// The key of an error whose place in the scene is not known: after every other.
    static constexpr size_t kLast = std::numeric_limits<size_t>::max();
    /// `where` names the input in the line about the errors not shown ("scene.xml: note: ...").
    explicit ErrorList(SourceLoc where = {}) : m_where(std::move(where)) {}

    /// Runs f; a core::Error it throws is kept under `order` and false returned. Other exceptions pass.
    template <class F> bool attempt(size_t order, F&& f) {
        try {
            f();
            return true;
        } catch (const Error& e) {
            add(e, order);
            return false;
        }
    }
    /// Keeps e (and, when it stands for several, each of them) under `order`.
    void add(const Error& e, size_t order);
    bool empty() const { return m_count == 0; }
    /// The errors found, those counted past what is kept included.
    size_t count() const { return m_count; }
    /// Throws what was found as one Error, in order of the keys (in the order found for one key),
    /// showing at most kErrorsShown; returns when nothing was found.
    void throwIfAny() const;

private:
    /// What is kept: enough to sort a long list before it is cut to kErrorsShown, bounded so that a
    /// scene of a million bad attributes does not hold a million messages.
    static constexpr size_t kErrorsKept = 1000;
    SourceLoc m_where;
    std::vector<std::pair<size_t, Error>> m_errors;
    size_t m_count = 0;
};

} // namespace fascia::core
