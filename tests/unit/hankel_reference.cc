// The reference values of parameters/infinite-plate-patch.prm and
// parameters/infinite-plate-dense-liquid.prm, computed here independently
// of the finite element code: the centre deflection and centre moment of
// an infinite Mindlin plate on a half-space or a dense liquid under a
// uniform circular patch (doc/verification.md, "Infinite plate under a
// patch"):
//   w(0)  = (P/(pi a)) Int_0^inf J1(k a) (1 + c k^2) / d(k) dk,
//   Mx(0) = D (1 + nu) P / (2 pi a) Int_0^inf J1(k a) k^2 / d(k) dk,
//   d(k) = D k^4 + (1 + c k^2) S(k),
//   c = D/(k_s G t), k_s = 5/6, and the foundation's stiffness per wave
//   number S(k) = E* k / 2 for the half-space, E* = E0/(1 - nu0^2), S = k_w
//   for a dense liquid of modulus k_w.
// (At the centre Mx = My = -D (1 + nu) lap(w_b)/2, w_b the bending part
// of w, whose transform is the net load over D k^4.) The integrands
// oscillate with period 2 pi / a and decay like k^-5/2: Gauss-Legendre on
// each half period of J1, the partial sums of the alternating tail
// averaged (Euler's first step). Cross-checked against mpmath (quadosc,
// 20 digits): w(0) = 1.9231820006778574e-4 m, Mx(0) = 10.803889266239927
// kNm/m on the half-space, w(0) = 1.4298256685594272e-4 m, Mx(0) =
// 11.108447591441248 kNm/m on the dense liquid. Also the Kirchhoff limits (c =
// 0, a -> 0) against the exact point-load value P l^2/(3 sqrt 3 D) on the
// half-space (doc/ verification.md), and on the dense liquid against
// Westergaard's interior formulas with Ioannides' correction, l^4 = D/k_w,
// gamma Euler's constant:
//   w(0)  = P/(8 k_w l^2) [1 + (ln(a/(2 l)) + gamma - 5/4) (a/l)^2/(2 pi)],
//   Mx(0) = (1 + nu) P/(4 pi) [ln(2 l/a) + 1/2 - gamma]
//           + (1 + nu) P (a/l)^2/128,
// series in a/l whose next terms are O((a/l)^4), about 0.006 (a/l)^4.

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <cmath>

#include "../tests.h"

/**
 * Int_0^inf (2 J1(ka)/(ka)) k g(k) / d(k) dk, whose first factor tends to
 * 1 as a -> 0 (the point load).
 */
/** The foundation: S(k) = E* k/2 (half-space) or k_w (dense liquid). */
struct Foundation
{
  double half_space_modulus; ///< E* (0 for a dense liquid)
  double subgrade_modulus;   ///< k_w (0 for the half-space)

  double
  stiffness(const double k) const
  {
    return half_space_modulus * k / 2. + subgrade_modulus;
  }
};

template <typename Numerator>
double
hankel_centre_integral(const double      D,
                       const double      c,
                       const Foundation &soil,
                       const double      a,
                       const Numerator  &g)
{
  const auto integrand = [&](const double k) {
    const double x      = k * a;
    const double factor = (x > 0) ? 2. * std::cyl_bessel_j(1, x) / x : 1.;
    return factor * k * g(k) /
           (D * k * k * k * k + (1. + c * k * k) * soil.stiffness(k));
  };
  const QGauss<1> gauss(12);
  const auto      integrate = [&](const double from, const double to) {
    // Below k = 20/m panels no wider than 0.25/m: the poles of 1/d(k) lie
    // about 1/l from the real axis, l of order 1 m here.
    double             integral = 0;
    const unsigned int panels =
      std::max(16u,
               static_cast<unsigned int>(
                 std::ceil(std::max(0., std::min(to, 20.) - from) / 0.25)));
    const double h = (to - from) / panels;
    for (unsigned int j = 0; j < panels; ++j)
      for (unsigned int q = 0; q < gauss.size(); ++q)
        integral +=
          gauss.weight(q) * h * integrand(from + (j + gauss.point(q)[0]) * h);
    return integral;
  };
  // Intervals between the zeros of J1(ka), asymptotically (n + 1/4) pi / a,
  // so that the tail alternates: average the last two partial sums. For a
  // point load the integrand does not oscillate; integrate far out.
  double sum = 0, previous = 0;
  if (a > 0)
    for (unsigned int n = 0; n < 20000; ++n)
      {
        previous = sum;
        sum +=
          integrate(n == 0 ? 0. : (n + 0.25) * M_PI / a, (n + 1.25) * M_PI / a);
      }
  else
    {
      // The point load's deflection (g = 1, c = 0): k g/d ~ 1/(D k^3) + ...,
      // integrate to K and add the tail's leading term.
      const double K = 1e4;
      for (double k = 0; k < K; k += 0.5)
        sum += integrate(k, k + 0.5);
      sum += (c == 0 ? 1. / (2. * D * K * K) : 0.);
      previous = sum;
    }
  return 0.5 * (sum + previous);
}

double
hankel_centre_deflection(const double      D,
                         const double      c,
                         const Foundation &soil,
                         const double      a,
                         const double      P)
{
  return P / (2. * M_PI) *
         hankel_centre_integral(D, c, soil, a, [c](const double k) {
           return 1. + c * k * k;
         });
}

double
hankel_centre_moment(const double      D,
                     const double      nu,
                     const double      c,
                     const Foundation &soil,
                     const double      a,
                     const double      P)
{
  return D * (1. + nu) * P / (4. * M_PI) *
         hankel_centre_integral(D, c, soil, a, [](const double k) {
           return k * k;
         });
}

int
main()
{
  initlog();
  // parameters/infinite-plate-patch.prm
  const double E = 3e7, nu = 0.15, t = 0.25, E0 = 1e5, nu0 = 0.35, a = 0.15,
               p          = 700.;
  const double     D      = E * t * t * t / (12. * (1. - nu * nu));
  const double     G      = E / (2. * (1. + nu));
  const double     c      = D / (5. / 6. * G * t);
  const double     E_star = E0 / (1. - nu0 * nu0);
  const double     P      = p * M_PI * a * a;
  const Foundation half_space{E_star, 0.};
  check("Mindlin plate, patch a = 0.15 m: w(0) [m]",
        hankel_centre_deflection(D, c, half_space, a, P),
        1.9231820006778574e-4,
        1e-8);
  check("value in parameters/infinite-plate-patch.prm",
        1.9231820e-4,
        hankel_centre_deflection(D, c, half_space, a, P),
        1e-7);
  check("Mindlin plate, patch a = 0.15 m: Mx(0) [kNm/m]",
        hankel_centre_moment(D, nu, c, half_space, a, P),
        10.803889266239927,
        1e-8);
  // Kirchhoff plate, point load: w0 = P l^2 / (3 sqrt 3 D), l^3 = 2 D/E*
  const double l = std::cbrt(2. * D * (1. - nu0 * nu0) / E0);
  check("Kirchhoff plate, point load: w(0) / (P l^2 / D)",
        hankel_centre_deflection(D, 0., half_space, 0., 1.) / (l * l / D),
        1. / (3. * std::sqrt(3.)),
        1e-6);

  // parameters/infinite-plate-dense-liquid.prm: the same slab and patch on
  // a dense liquid of k_w = 5e4 kN/m^3.
  const double     k_w = 5e4;
  const Foundation dense_liquid{0., k_w};
  const double     w_dense = hankel_centre_deflection(D, c, dense_liquid, a, P);
  const double     M_dense = hankel_centre_moment(D, nu, c, dense_liquid, a, P);
  check("Mindlin plate on a dense liquid, patch a = 0.15 m: w(0) [m]",
        w_dense,
        1.4298256685594272e-4,
        1e-8);
  check("Mindlin plate on a dense liquid, patch a = 0.15 m: Mx(0) [kNm/m]",
        M_dense,
        11.108447591441248,
        1e-8);
  // Kirchhoff (c = 0) against Westergaard and Ioannides, for two patch
  // radii: the difference is the series' next term, O((a/l)^4).
  const double l_w   = std::pow(D / k_w, 0.25);
  const double gamma = 0.57721566490153286;
  for (const double ratio : {0.2, 0.05})
    {
      const double radius = ratio * l_w;
      const double load   = 1.;
      const double westergaard_w =
        load / (8. * k_w * l_w * l_w) *
        (1. + (std::log(radius / (2. * l_w)) + gamma - 1.25) * ratio * ratio /
                (2. * M_PI));
      const double westergaard_M =
        (1. + nu) * load / (4. * M_PI) *
          (std::log(2. * l_w / radius) + 0.5 - gamma) +
        (1. + nu) * load * ratio * ratio / 128.;
      const double tolerance = 0.02 * std::pow(ratio, 4);
      check("Kirchhoff plate on a dense liquid, a/l = " +
              std::to_string(ratio).substr(0, 4) + ": w(0), Westergaard",
            hankel_centre_deflection(D, 0., dense_liquid, radius, load),
            westergaard_w,
            tolerance);
      check("Kirchhoff plate on a dense liquid, a/l = " +
              std::to_string(ratio).substr(0, 4) +
              ": Mx(0), Westergaard-Ioannides",
            hankel_centre_moment(D, nu, 0., dense_liquid, radius, load),
            westergaard_M,
            tolerance);
    }
}
