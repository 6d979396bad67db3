#include "fascia/base/ErrorList.h"

#include <algorithm>

namespace fascia::core {

void ErrorList::add(const Error& e, size_t order) {
    // an error that stands for several (a nested load that gathered its own) is taken apart, so that
    // the list stays flat and the limit counts single errors
    std::vector<Error> singles{Error(e.kind(), e.loc(), e.message(), e.notes())};
    singles.insert(singles.end(), e.more().begin(), e.more().end());
    for (Error& s : singles) {
        ++m_count;
        if (m_errors.size() < kErrorsKept) m_errors.emplace_back(order, std::move(s));
    }
    m_count += e.unshown();
}

void ErrorList::throwIfAny() const {
    if (m_errors.empty()) return;
    std::vector<std::pair<size_t, Error>> sorted = m_errors;
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const size_t shown = std::min(sorted.size(), kErrorsShown);
    if (m_count == 1) throw sorted.front().second;
    std::vector<Error> more;
    for (size_t i = 1; i < shown; ++i) more.push_back(sorted[i].second);
    throw Error(sorted.front().second, std::move(more), m_count - shown, m_where);
}

} // namespace fascia::core
