#pragma once
/// The per-element arithmetic of a Prony-series relaxation of the second Piola-Kirchhoff stress
/// (TLED eq. (24), (29), (30)), for the device step's element kernels
/// (plugins/cuda/include/fascia/cuda/StepKernels.h). With the law's response split into its
/// isochoric and volumetric parts (Tensor3.h secondPiola), each series relaxes one part or both:
///   Y_i^n = A_i R^n + B_i Y_i^(n-1)   (TLED eq. (30), the backward-Euler step of eq. (29))
///   S^n = Phi^n - sum_i Y_i^n         (TLED eq. (24))
/// with Phi = Siso + Svol, R the relaxed part, A_i and B_i from viscoelastic::ViscoelasticProny.
///
/// TLEDForceField's vectorised batch loops (plugins/tled/TLEDKernel.h restSplit, viscousStress,
/// viscousStressOneTerm, stressOutput) write the same two expressions inline. Calling these functions
/// from there, however inlined, changes how GCC 12 vectorises TLED's element loops (its basic-block
/// vectorisation of the scalar stress loop, hence which products are fused) and with it TLED's
/// forces and stresses in the last bits, for built-in and user laws alike (measured when this was
/// written); TLED's results are kept bitwise, so the expressions stay written there too. A change to
/// either must be made to both: test_cuda_emulation compares the device step with TLEDForceField
/// to 1e-11 with every law and apply value and fails on a divergence.
#include "fascia/elements/Tensor3.h"

#include <algorithm>

namespace fascia::elements {

/// Moves s ln J from the isochoric to the volumetric part of a law's response (dJiso -= s/J,
/// dJvol += s/J, their sum unchanged), so that each part a series relaxes alone is stress-free at
/// rest (fascia/materials/RelaxationSplit.h). max(J0, J) keeps the quotient finite for crushed
/// elements (and unused batch lanes).
template <class T>
FASCIA_HD FASCIA_INLINE void restShift(T& dJiso, T& dJvol, T J, T shift, T J0) {
    const T q = shift / std::max(J0, J);
    dJiso -= q;
    dJvol += q;
}

/// One step of a Prony term's state (TLED eq. (30)): Y^n = A R^n + B Y^(n-1), R the relaxed part of
/// one stress component.
template <class T>
FASCIA_HD FASCIA_INLINE T pronyState(T A, T R, T B, T Yprev) {
    return A * R + B * Yprev;
}

} // namespace fascia::elements
