#pragma once
/// Node arrays as numpy views of the simulation's memory, no copies: an (n, 3) float64 array whose
/// base is a ViewRef. The ViewRef keeps the simulation alive (the memory never dangles) and tells
/// whether the array still stands for the state: it does not after the simulation is closed or the
/// state's storage moved (a topology change resizes it). fascia.View (fascia/_views.py) checks it at
/// every indexing, ufunc and print, and raises fascia.StaleViewError.
#include "Holder.h"

#include <pybind11/numpy.h>

namespace fascia::python {

class ViewRef {
public:
    ViewRef(std::shared_ptr<Holder> h, const Positions* array, std::string label)
        : m_holder(std::move(h)), m_array(array), m_data(core::flat(*array)), m_size(array->size()), m_label(std::move(label)) {}
    /// "" when the view is valid, else why not.
    std::string problem() const;
    const std::string& label() const { return m_label; }

private:
    std::shared_ptr<Holder> m_holder;
    const Positions* m_array;
    const double* m_data;
    size_t m_size;
    std::string m_label;
};

/// The view of `array` (read-only unless writeable; a writeable one is watched for NaN).
py::array nodeView(const std::shared_ptr<Holder>& h, Positions& array, const std::string& label, bool writeable);
/// Raises fascia.StateError when a watched array holds NaN or infinity (written through a view).
void checkWritten(const Holder& h);
void bindViews(py::module_& m);

} // namespace fascia::python
