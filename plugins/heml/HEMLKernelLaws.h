#pragma once
/// Internal to HEMLForceField: the instantiations of the HEML element loop (HEMLKernel.h) for one
/// scalar type T: how a chunk's law is evaluated (the inlined built-in law, the batched virtual call
/// of any other material, the mass springs), and the loops of a material from the one list of
/// built-in laws (elements/LawDispatch.h). Included by HEMLKernelDouble.cpp and HEMLKernelFloat.cpp,
/// one scalar type each (they compile in parallel).
#include "HEMLKernel.h"

#include "fascia/elements/LawDispatch.h"

namespace fascia::heml {

/// An inlined built-in law, evaluated in T (the laws are templated on the scalar, Material.h).
template <class Law>
struct LawEval {
    static constexpr bool spring = false;
    const Law& law;
    unsigned uses() const { return Law::uses; }
    template <class T>
    void operator()(Chunk<T>& c, double J0) const {
        // plain auto-vectorisation: "omp simd" would privatise the structs into arrays and fail
#pragma GCC ivdep
        for (int j = 0; j < kLanes; ++j) {
            materials::InvariantsT<T> in;
            in.I1 = c.I1[j];
            in.I2 = c.I2[j];
            in.J = c.J[j];
            in.I4 = c.I4[j];
            in.I6 = c.I6[j];
            materials::ResponseT<T> r;
            materials::evaluateLaw(law, in, J0, r);
            c.store(j, r);
        }
    }
};

/// Any material: one virtual call per chunk. BaseMaterial::evaluate is double only, so a float
/// chunk's invariants go in as double and the response comes back rounded to float.
struct GenericEval {
    static constexpr bool spring = false;
    const materials::BaseMaterial* m;
    unsigned usesBits;
    unsigned uses() const { return usesBits; }
    template <class T>
    void operator()(Chunk<T>& c, double J0) const {
        for (int j = 0; j < kLanes; ++j)
            c.inv[j] = materials::Invariants{double(c.I1[j]), double(c.I2[j]), double(c.J[j]), double(c.I4[j]), double(c.I6[j])};
        m->evaluate(c.inv, c.resp, kLanes, J0);
        for (int j = 0; j < kLanes; ++j) {
            c.store(j, c.resp[j]);
        }
    }
};

/// Mass-spring energy of HEML eq. (38).
struct SpringEval {
    static constexpr bool spring = true;
    unsigned uses() const { return 0; }
};

namespace kernel_laws {

using materials::BaseMaterial;

template <class T, class Law, bool Forces, bool Visco>
double runLaw(Impl& d, size_t b, const BlockRun& x) {
    const BaseMaterial* m = d.materials[size_t(d.blocks[b].material)];
    if constexpr (std::is_same_v<Law, elements::GenericLaw>)
        return runBlock<T, GenericEval, Forces, Visco>(d, b, GenericEval{m, m->uses()}, x);
    else
        return runBlock<T, LawEval<Law>, Forces, Visco>(d, b, {elements::lawOf<Law>(m)}, x);
}

template <class T, bool Forces, bool Visco>
double runSpring(Impl& d, size_t b, const BlockRun& x) {
    return runBlock<T, SpringEval, Forces, Visco>(d, b, SpringEval{}, x);
}

} // namespace kernel_laws

template <class T>
Impl::Loops loopsIn(const materials::BaseMaterial* m) {
    using namespace kernel_laws;
    if (!m) return Impl::Loops{&runSpring<T, true, true>, &runSpring<T, true, false>, &runSpring<T, false, false>, true};
    return elements::selectForLaw(m, [](auto tag) {
        using Law = typename decltype(tag)::type;
        return Impl::Loops{&runLaw<T, Law, true, true>, &runLaw<T, Law, true, false>, &runLaw<T, Law, false, false>,
                           !std::is_same_v<Law, elements::GenericLaw>};
    });
}

} // namespace fascia::heml
