// TLEDForceField::layoutBytes: the bytes one addForce moves, counted from the arrays after init
// (core::LayoutBytes: each array once per pass that reads it, once more per pass that writes it).
#include "TLEDData.h"

namespace fascia::tled {

namespace {
/// What the element loop reads of one element kind: the packed rows (dN/dX, hourglass vectors,
/// fibres; in float when mixed), the volumes, the connectivity and (hexahedra) the hourglass stiffness.
template <int NN>
size_t elementBytes(const ElementSet<NN>& es) {
    // mixed: the float pack holds the volumes (ElementSet::volRow), the double volumes are not read
    const size_t vol = es.volRow >= 0 ? 0 : es.vol.size() * sizeof(double);
    return es.pack.size() * sizeof(double) + es.packF.size() * sizeof(float) + vol + es.nodes.size() * sizeof(int) +
           es.hgK.size() * sizeof(double);
}
} // namespace

core::LayoutBytes TLEDForceField::layoutBytes() const {
    const Impl& im = *m_impl;
    // the block buffers, f and nodeOf (compact: u copied into the rows, the per-node row lists)
    core::LayoutBytes b = im.compact ? im.rows.stepBytes() : im.buffers.stepBytes();
    b.elementData = elementBytes(im.tet) + elementBytes(im.hex);
    for (const ViscoSet& vs : im.visco) b.elementData += (vs.Yprev.size() + vs.Ycur.size()) * sizeof(double);
    // displacements: x and X read (3 doubles a node), u written (4 a node); the kernel reads u once
    const size_t n = im.nodeCount;
    b.nodeRows += 2 * 3 * n * sizeof(double) + 2 * 4 * n * sizeof(double);
    return b;
}

} // namespace fascia::tled
