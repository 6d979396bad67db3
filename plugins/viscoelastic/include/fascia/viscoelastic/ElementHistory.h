#pragma once
/// A force field whose Prony states a step backend advances in its own memory (the device step,
/// plugins/cuda): the backend hands them back with its history clock, so that the force field's
/// stress output (cellData: S, the Cauchy and von Mises stresses) is that of the relaxed material,
/// as after a step on the CPU. TLEDForceField and HEMLForceField implement it.
#include "fascia/viscoelastic/HistoryClock.h"

#include <vector>

namespace fascia::viscoelastic {

class ElementHistory {
public:
    virtual ~ElementHistory();
    /// The states after an evaluation at clock's last time, in the backend's layout: term k (the
    /// terms of the force field's series in their order, one after the other) and component c of
    /// tetrahedron e (input order) at Yt[(6 k + c) nTets + e], of hexahedron e at Yh[(6 k + c) nHexes
    /// + e]; c counts the stress components xx yy zz xy yz xz (TLED) or the six link coefficients
    /// (HEML). They become both the committed and the current states, and clock the force field's.
    virtual void adoptHistory(const std::vector<double>& Yt, const std::vector<double>& Yh, const HistoryClock& clock) = 0;
};

} // namespace fascia::viscoelastic
