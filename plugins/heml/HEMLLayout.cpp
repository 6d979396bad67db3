// HEMLForceField::layoutBytes: the bytes one addForce moves, counted from the arrays after init
// (core::LayoutBytes: each array once per pass that reads it, once more per pass that writes it).
#include "HEMLData.h"

namespace fascia::heml {

core::LayoutBytes HEMLForceField::layoutBytes() const {
    const Impl& d = *m_impl;
    core::LayoutBytes b = d.rows.stepBytes();  // positions in, the rows, their sum into f
    constexpr size_t D = sizeof(double);
    // per slot, what the element loop reads: the node rows, the volume, 1 / det V (J) and G; the
    // fibre terms and the spring data where present (empty arrays otherwise). 8 bytes each in
    // double precision, 4 in mixed (the other precision's arrays are empty)
    size_t e = d.el.bytes() + d.elf.bytes();
    for (const auto& n : d.node) e += n.size() * sizeof(int);
    // viscosity: the committed history read, the current states written
    for (const auto& y : d.Yprev) e += y.size() * D;
    for (const auto& y : d.Ycur) e += y.size() * D;
    b.elementData = e;
    return b;
}

} // namespace fascia::heml
