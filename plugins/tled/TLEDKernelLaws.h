#pragma once
/// Internal to TLEDForceField: the instantiations of the TLED element loop for one scalar type T:
/// per element kind, the inlined loop of every built-in law (from the one list,
/// materials::BuiltinMaterials) and the generic loop for any other material. Included by
/// TLEDKernelDouble.cpp and TLEDKernelFloat.cpp, one scalar type each (they compile in parallel).
#include "TLEDKernel.h"

#include "fascia/elements/LawDispatch.h"

namespace fascia::tled {

namespace kernel_laws {

using kernel::Batch;
using materials::InvariantsT;
using materials::ResponseT;

template <class S, class T>
FASCIA_INLINE void storeResponse(S& s, int k, const ResponseT<T>& r) {
    s.r.W[k] = r.W;
    s.r.d1[k] = r.dI1;
    s.r.d2[k] = r.dI2;
    s.r.d4[k] = r.dI4;
    s.r.d6[k] = r.dI6;
    s.r.dJi[k] = r.dJiso;
    s.r.dJv[k] = r.dJvol;
}

template <int NN, class Law, class T>
void kernelLaw(const TLEDForceField::Impl& im, const Block& b, const KernelIO& io) {
    const Law law = *static_cast<const Law*>(im.groups[static_cast<size_t>(b.group)].law);
    const double J0 = im.J0;
    kernel::runKernel<NN, Law::uses, T>(im, b,
                                     [&](Batch<NN, T>& s, int n) {
                                         // no 'omp simd' here: it would turn the structs into arrays of
                                         // structs; plain auto-vectorisation scalarises them
                                         for (int k = 0; k < n; ++k) {
                                             InvariantsT<T> in;
                                             in.I1 = s.I1[k];
                                             in.I2 = s.I2[k];
                                             in.J = s.J[k];
                                             in.I4 = s.I4[k];
                                             in.I6 = s.I6[k];
                                             ResponseT<T> r;
                                             materials::evaluateLaw(law, in, J0, r);  // branch-free
                                             storeResponse(s, k, r);
                                         }
                                     },
                                     io);
}

/// (In float the invariants are widened to double for the material's evaluate() and its response
/// rounded back: a user law needs only its double form.)
template <int NN, unsigned U, class T>
void kernelGeneric(const TLEDForceField::Impl& im, const Block& b, const KernelIO& io) {
    const materials::BaseMaterial* m = im.groups[static_cast<size_t>(b.group)].material;
    const double J0 = im.J0;
    kernel::runKernel<NN, U, T>(im, b,
                             [&](Batch<NN, T>& s, int n) {
                                 materials::Invariants in[kBatch];
                                 materials::Response out[kBatch];
                                 for (int k = 0; k < n; ++k) {
                                     in[k].I1 = s.I1[k];
                                     in[k].I2 = s.I2[k];
                                     in[k].J = s.J[k];
                                     in[k].I4 = s.I4[k];
                                     in[k].I6 = s.I6[k];
                                 }
                                 m->evaluate(in, out, static_cast<size_t>(n), J0);
                                 for (int k = 0; k < n; ++k) {
                                     const materials::Response& o = out[k];
                                     storeResponse(s, k, ResponseT<T>{T(o.W), T(o.dI1), T(o.dI2), T(o.dI4), T(o.dI6), T(o.dJiso), T(o.dJvol)});
                                 }
                             },
                             io);
}

template <int NN, class T, unsigned... U>
TLEDForceField::Impl::KernelFn genericFor(unsigned uses, std::integer_sequence<unsigned, U...>) {
    static const TLEDForceField::Impl::KernelFn table[] = {&kernelGeneric<NN, U, T>...};
    return table[uses & 7u];
}

} // namespace kernel_laws

template <class T>
TLEDForceField::Impl::KernelFn kernelFor(const TLEDForceField::Impl::Group& g, const void*& law) {
    using namespace kernel_laws;
    using Fn = TLEDForceField::Impl::KernelFn;
    law = nullptr;
    return elements::selectForLaw(g.material, [&](auto tag) -> Fn {
        using Law = typename decltype(tag)::type;
        if constexpr (std::is_same_v<Law, elements::GenericLaw>) {
            // any other material: its batched evaluate(), with the invariants it declares it uses
            return g.kind == 0 ? genericFor<4, T>(g.uses, std::make_integer_sequence<unsigned, 8>{})
                               : genericFor<8, T>(g.uses, std::make_integer_sequence<unsigned, 8>{});
        } else {
            law = &elements::lawOf<Law>(g.material);
            return g.kind == 0 ? &kernelLaw<4, Law, T> : &kernelLaw<8, Law, T>;
        }
    });
}

} // namespace fascia::tled
