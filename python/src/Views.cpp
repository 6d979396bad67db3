#include "Views.h"
#include "Errors.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace fascia::python {

std::string ViewRef::problem() const {
    if (m_holder->closed) return m_label + ": " + m_holder->closedWhy;
    if (m_array->size() != m_size || core::flat(*m_array) != m_data)
        return m_label + ": the state's storage changed (a topology change): take the view again";
    return {};
}

py::array nodeView(const std::shared_ptr<Holder>& h, Positions& array, const std::string& label, bool writeable) {
    if (writeable) {
        bool known = false;
        for (auto& w : h->watched) known |= w.array == &array;
        if (!known) h->watched.push_back({&array, label});
    }
    py::object ref = py::cast(ViewRef(h, &array, label));
    const auto n = py::ssize_t(array.size());
    static double empty[3] = {0, 0, 0};
    double* data = array.empty() ? empty : core::flat(array);
    py::array a(py::dtype::of<double>(), {n, py::ssize_t(3)}, {py::ssize_t(3 * sizeof(double)), py::ssize_t(sizeof(double))},
                data, ref);
    if (!writeable) a.attr("flags").attr("writeable") = false;
    return a;
}

void checkWritten(const Holder& h) {
    for (const auto& w : h.watched) {
        const double* p = core::flat(*w.array);
        const size_t n = 3 * w.array->size();
        // NaN and infinity are the doubles whose 11 exponent bits are all set: a branch-free pass
        // with an integer OR (it vectorises, where a floating-point sum may not be reordered), the
        // place looked for only when it finds one
        constexpr std::uint64_t kExponent = 0x7ff0000000000000ull;
        std::uint64_t bad = 0;
        for (size_t i = 0; i < n; ++i) {
            std::uint64_t bits;
            std::memcpy(&bits, p + i, sizeof bits);
            bad |= std::uint64_t((bits & kExponent) == kExponent);
        }
        if (!bad) continue;
        for (size_t i = 0; i < n; ++i)
            if (!std::isfinite(p[i])) {
                const char* axis[] = {"x", "y", "z"};
                raise("StateError", w.label + "[" + std::to_string(i / 3) + ", " + std::to_string(i % 3) + "] (" +
                                        axis[i % 3] + " of node " + std::to_string(i / 3) + ") is " + std::to_string(p[i]) +
                                        ": a value written through a view must be finite; nothing was stepped");
            }
    }
}

void bindViews(py::module_& m) {
    py::class_<ViewRef>(m, "ViewRef", "What a node view stands for (fascia.View checks it).")
        .def("problem", &ViewRef::problem, "'' when the view is valid, else why it is not")
        .def_property_readonly("label", &ViewRef::label);
}

} // namespace fascia::python
