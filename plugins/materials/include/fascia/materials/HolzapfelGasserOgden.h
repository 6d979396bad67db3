#pragma once
/// Holzapfel-Gasser-Ogden: a neo-Hookean ground matrix with exponential collagen fibres, for
/// arteries, ligaments and tendons. The law struct (inlined by the force fields, see Material.h)
/// and its component.
#include "fascia/materials/FastExp.h"
#include "fascia/materials/Laws.h"
#include "fascia/materials/Moduli.h"

#include <cmath>

namespace fascia::materials {

/// The isochoric part of Holzapfel, Gasser & Ogden (2000, J. Elasticity 61) with the fibre
/// dispersion of Gasser, Ogden & Holzapfel (2006, J. R. Soc. Interface 3), composed with FEBio's
/// volumetric part k/2 (ln J)^2 (LogVolume: it grows without bound as J -> 0), where
///   E_i = kappa (I1bar - 3) + (1 - 3 kappa)(I_ibar - 1),   I1bar = J^(-2/3) I1, I_ibar = J^(-2/3) I_i,
/// with I4 = a0.C a0, I6 = b0.C b0, dispersion 0 <= kappa <= 1/3 (0: all fibres along a0, 1/3:
/// isotropic fibres), <E> = max(E, 0).
/// - Fibres act only in tension, by an exact switch (the Macaulay bracket <E>): the fibre term and
///   its first derivative k1 E exp(k2 E^2) are continuous at E = 0, so W is C^1 (its second
///   derivative jumps from 0 to k1 there).
/// - k2 = 0 is allowed (fibres k1/2 <E>^2): the fibre energy is written k1/2 <E>^2 (e^x - 1)/x with
///   x = k2 <E>^2 (fastExprel), exact at x = 0 and without cancellation near it.
/// - One fibre family: `twoFamilies` false, and E_6 is taken as 0 (I6 is still read; the second
///   direction then only fills the slot).
/// Derivatives w.r.t. the plain invariants (Material.h): with w1 = dW/dI1bar = mu/2 + kappa (g4 + g6),
/// w4 = (1 - 3 kappa) g4, w6 = (1 - 3 kappa) g6, g_i = k1 <E_i> exp(k2 <E_i>^2):
///   dI1 = J^(-2/3) w1, dI4 = J^(-2/3) w4, dI6 = J^(-2/3) w6,
///   dJiso = -2/(3 J) (w1 I1bar + w4 I4bar + w6 I6bar).
/// Stress-free at rest (E_i = 0 there). No libm: invCbrt, fastExp, fastExprel (and fastLog in U).
struct HolzapfelGasserOgdenIso {
    static constexpr unsigned uses = BaseMaterial::UsesI4 | BaseMaterial::UsesI6;
    static constexpr const char* kEnergy = "mu/2 (I1bar - 3) + k1/(2 k2) sum_{i=4,6} [exp(k2 <E_i>^2) - 1]";
    static constexpr bool kStressFreeAtRest = true;
    double mu = 0;          ///< shear modulus of the matrix (Pa)
    double k1 = 0;          ///< fibre stiffness (Pa)
    double k2 = 0;          ///< fibre exponent (dimensionless)
    double dispersion = 0;  ///< kappa in [0, 1/3]
    bool twoFamilies = false;
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T mu = T(this->mu), k1 = T(this->k1), k2 = T(this->k2);
        const T dispersion = T(this->dispersion), b = T(1.0 - 3.0 * this->dispersion);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2, I4b = in.I4 * t2, I6b = in.I6 * t2;
        const T d1 = I1b - T(3);
        const T E4 = std::max(dispersion * d1 + b * (I4b - T(1)), T(0));
        const T E6 = twoFamilies ? std::max(dispersion * d1 + b * (I6b - T(1)), T(0)) : T(0);
        const T x4 = k2 * E4 * E4, x6 = k2 * E6 * E6;
        const T g4 = k1 * E4 * fastExp(x4), g6 = k1 * E6 * fastExp(x6);
        r.W += T(0.5) * mu * d1 + T(0.5) * k1 * (E4 * E4 * fastExprel(x4) + E6 * E6 * fastExprel(x6));
        const T w1 = T(0.5) * mu + dispersion * (g4 + g6), w4 = b * g4, w6 = b * g6;
        r.dI1 += w1 * t2;
        r.dI4 += w4 * t2;
        r.dI6 += w6 * t2;
        r.dJiso += -T(2.0 / 3.0) * (w1 * I1b + w4 * I4b + w6 * I6b) * iJ;
    }
};
using HolzapfelGasserOgdenLaw = ComposedLaw<HolzapfelGasserOgdenIso, LogVolume>;

/// The Holzapfel-Gasser-Ogden material (see HolzapfelGasserOgdenLaw for W and its derivatives).
/// Parameters: mu, k1, k2, dispersion (FEBio's "kappa"), bulkModulus (FEBio's "k"), direction
/// (a0) and, for a second family, direction2 (b0); FEBio's fibre angle gamma is given here as the
/// two directions themselves. Force fields may take the directions per element from mesh cell
/// arrays instead; the second family exists only when direction2 is set here (a mesh array of
/// second directions alone does not switch it on). Stress-free at rest; small-strain shear modulus
/// mu, bulk modulus k = bulkModulus.
/// The stable time step (from waveSpeed) is a rest value: the fibres stiffen exponentially, so
/// large fibre strains need a smaller step than the rest estimate.
class HolzapfelGasserOgden : public Material<HolzapfelGasserOgdenLaw> {
public:
    static constexpr const char* kName = "HolzapfelGasserOgden";
    /// moderate soft-tissue parameters (Pa) for sweeps and examples: name=value pairs separated by ";"
    static constexpr const char* kExample = "mu=1000;k1=3000;k2=4;dispersion=0.1;bulkModulus=20000;direction=1 0.2 0.3;direction2=-0.2 1 0.4";
    static constexpr const char* kTitle =
        "Holzapfel-Gasser-Ogden (Gasser, Ogden and Holzapfel 2006), fibres in tension only, one or two families";
    static constexpr const char* kTerms =
        "E_i = kappa (I1bar - 3) + (1 - 3 kappa)(I_ibar - 1), <E> = max(E, 0), I1bar = J^(-2/3) tr C, I4bar = J^(-2/3) a0.C a0, I6bar = J^(-2/3) b0.C b0 (i = 6 only with direction2), kappa = dispersion, k = bulkModulus, k2 = 0: k1/2 <E_i>^2";
    void init() override {
        m_law.mu = m_mu.get();
        m_law.k1 = m_k1.get();
        m_law.k2 = m_k2.get();
        m_law.dispersion = m_dispersion.get();
        m_law.k = m_bulk.get();
        m_a0 = unitDirection(*this, m_dir);
        m_law.twoFamilies = m_dir2.isSet();
        m_b0 = m_a0;
        if (m_law.twoFamilies) {
            m_b0 = unitDirection(*this, m_dir2);
            if (std::abs(m_a0.dot(m_b0)) > 1.0 - 1e-9)
                fail(m_dir2, "'direction2' is parallel to 'direction': give two distinct fibre families, or leave "
                             "'direction2' unset for one family");
        }
    }
    double shearModulus() const override { return m_law.mu; }
    double bulkModulus() const override { return m_law.k; }
    /// Upper bound of the dilatational wave speed at rest: sqrt((k + 4/3 mu + n eta)/rho), with
    /// eta = 2 k1 (1 - 3 kappa)^2 the small-strain fibre stiffness (each family's energy is
    /// eta (a0.dev(eps) a0)^2 there, as TransverselyIsotropic's eta/4 (I4bar - 1)^2) and n the number
    /// of families.
    double waveSpeed(double rho) const override {
        const double b = 1.0 - 3.0 * m_law.dispersion;
        const double eta = 2.0 * m_law.k1 * b * b * (m_law.twoFamilies ? 2.0 : 1.0);
        return std::sqrt((m_law.k + 4.0 / 3.0 * m_law.mu + eta) / rho);
    }
    const Vec3* fibreDirection(int which) const override {
        return which == 0 ? &m_a0 : which == 1 ? &m_b0 : nullptr;
    }
    const Vec3& direction() const { return m_a0; }  ///< unit a0
    /// Unit b0 (with one family: a0 again, a placeholder the law does not use).
    const Vec3& direction2() const { return m_b0; }

    core::Param<double> m_mu{this, core::ParamSpec("mu").unit("Pa").above(0).required().help("shear modulus mu of the matrix, mu/2 (I1bar - 3)")};
    core::Param<double> m_k1{this, core::ParamSpec("k1").unit("Pa").min(0).required().help("fibre stiffness k1 of k1/(2 k2) [exp(k2 <E>^2) - 1]")};
    core::Param<double> m_k2{this, core::ParamSpec("k2").min(0).required().help("dimensionless fibre exponent k2 (0: quadratic fibres k1/2 <E>^2)")};
    core::Param<double> m_dispersion{this, core::ParamSpec("dispersion").min(0).max(1.0 / 3.0).help("fibre dispersion kappa of E = kappa (I1bar - 3) + (1 - 3 kappa)(I4bar - 1): 0 aligned, 1/3 isotropic (FEBio's kappa)"), 0.0};
    core::Param<double> m_bulk{this, core::ParamSpec("bulkModulus").unit("Pa").above(0).required().help("bulk modulus k of k/2 (ln J)^2 (FEBio's k)")};
    core::Param<Vec3> m_dir{this, core::ParamSpec("direction").help("first fibre direction a0 (I4 = a0.C a0) in the reference configuration (normalised)"), Vec3(0, 0, 1)};
    core::Param<Vec3> m_dir2{this, core::ParamSpec("direction2").help("second fibre direction b0 (I6 = b0.C b0, normalised); unset: one fibre family")};

private:
    Vec3 m_a0 = Vec3(0, 0, 1), m_b0 = Vec3(0, 0, 1);
};

} // namespace fascia::materials
