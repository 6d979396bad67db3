// The instantiations of the TLED element loop: per element kind, the inlined loop of every built-in
// law (from the one list, materials::BuiltinMaterials) and the generic loop for any other material.
#include "TLEDKernel.h"

#include "fascia/elements/LawDispatch.h"

namespace fascia::tled {

namespace {

using kernel::Batch;
using materials::Invariants;
using materials::Response;

template <class S>
FASCIA_INLINE void storeResponse(S& s, int k, const Response& r) {
    s.r.W[k] = r.W;
    s.r.d1[k] = r.dI1;
    s.r.d2[k] = r.dI2;
    s.r.d4[k] = r.dI4;
    s.r.d6[k] = r.dI6;
    s.r.dJi[k] = r.dJiso;
    s.r.dJv[k] = r.dJvol;
}

template <int NN, class Law>
void kernelLaw(const TLEDForceField::Impl& im, const Block& b, const KernelIO& io) {
    const Law law = *static_cast<const Law*>(im.groups[static_cast<size_t>(b.group)].law);
    const double J0 = im.J0;
    kernel::runKernel<NN, Law::uses>(im, b,
                                     [&](Batch<NN>& s, int n) {
                                         // no 'omp simd' here: it would turn the structs into arrays of
                                         // structs; plain auto-vectorisation scalarises them
                                         for (int k = 0; k < n; ++k) {
                                             Invariants in;
                                             in.I1 = s.I1[k];
                                             in.I2 = s.I2[k];
                                             in.J = s.J[k];
                                             in.I4 = s.I4[k];
                                             in.I6 = s.I6[k];
                                             Response r;
                                             materials::evaluateLaw(law, in, J0, r);  // branch-free
                                             storeResponse(s, k, r);
                                         }
                                     },
                                     io);
}

template <int NN, unsigned U>
void kernelGeneric(const TLEDForceField::Impl& im, const Block& b, const KernelIO& io) {
    const materials::BaseMaterial* m = im.groups[static_cast<size_t>(b.group)].material;
    const double J0 = im.J0;
    kernel::runKernel<NN, U>(im, b,
                             [&](Batch<NN>& s, int n) {
                                 Invariants in[kBatch];
                                 Response out[kBatch];
                                 for (int k = 0; k < n; ++k) {
                                     in[k].I1 = s.I1[k];
                                     in[k].I2 = s.I2[k];
                                     in[k].J = s.J[k];
                                     in[k].I4 = s.I4[k];
                                     in[k].I6 = s.I6[k];
                                 }
                                 m->evaluate(in, out, static_cast<size_t>(n), J0);
                                 for (int k = 0; k < n; ++k) storeResponse(s, k, out[k]);
                             },
                             io);
}

template <int NN, unsigned... U>
TLEDForceField::Impl::KernelFn genericFor(unsigned uses, std::integer_sequence<unsigned, U...>) {
    static const TLEDForceField::Impl::KernelFn table[] = {&kernelGeneric<NN, U>...};
    return table[uses & 7u];
}

} // namespace

void chooseKernel(TLEDForceField::Impl::Group& g) {
    using Fn = TLEDForceField::Impl::KernelFn;
    g.law = nullptr;
    g.fn = elements::selectForLaw(g.material, [&](auto tag) -> Fn {
        using Law = typename decltype(tag)::type;
        if constexpr (std::is_same_v<Law, elements::GenericLaw>) {
            // any other material: its batched evaluate(), with the invariants it declares it uses
            return g.kind == 0 ? genericFor<4>(g.uses, std::make_integer_sequence<unsigned, 8>{})
                               : genericFor<8>(g.uses, std::make_integer_sequence<unsigned, 8>{});
        } else {
            g.law = &elements::lawOf<Law>(g.material);
            return g.kind == 0 ? &kernelLaw<4, Law> : &kernelLaw<8, Law>;
        }
    });
}

} // namespace fascia::tled
