#pragma once
// Private to the study module: Andrews' squeezing mechanism in the IVP Test Set's 7 relative
// coordinates q = (β, Θ, γ, Φ, δ, Ω, ε), M(q) q'' = f(q, q') − G(q)ᵀλ, g(q) = 0, with M, f and g
// exactly as in shared/andrews.md §1.3 (Mazzia, Magherini et al., problem "andrews"; Hairer &
// Wanner II, Sec. VII.7). The C++ twin of scripts/reference/andrews_reference.py, for the IDA peer;
// tests/study check it against the test set's published angles at t = 0.03.
#include <Eigen/Dense>
#include <array>
#include <cmath>

namespace alphaflex::study::andrews {

using Vec7 = Eigen::Matrix<double, 7, 1>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat7 = Eigen::Matrix<double, 7, 7>;
using Mat67 = Eigen::Matrix<double, 6, 7>;

// andrews.md §1.1 (SI units).
constexpr double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050, m6 = .00706, m7 = .05498;
constexpr double I1 = 2.194e-6, I2 = 4.410e-7, I3 = 5.255e-6, I4 = 5.667e-7, I5 = 1.169e-5, I6 = 5.667e-7,
                 I7 = 1.912e-5;
constexpr double xa = -.06934, ya = -.00227, xb = -.03635, yb = .03273, xc = .014, yc = .072;
constexpr double rr = .007, ra = .00092, d = .028, da = .0115, ss = .035, sa = .01874, sb = .01043, sc = .018,
                 sd = .02;
constexpr double e = .02, ea = .01421, zt = .04, ta = .02308, tb = .00916, zf = .02, fa = .01421, u = .04,
                 ua = .01228, ub = .00449;
constexpr double mom = .033, c0 = 4530., l0 = .07785;

/// Consistent initial angles (andrews.md §1.4); the mechanism starts at rest.
inline Vec7 initial_angles() {
  Vec7 q;
  q << -0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449, 0.222668390165885884674473185609,
      0.487364979543842550225598953530, -0.222668390165885884674473185609, 1.23054744454982119249735015568;
  return q;
}

/// One term coef·cos(P·q) or coef·sin(P·q) of a loop-closure equation.
struct Term {
  double coef;
  bool cosine;
  std::array<int, 7> P;
};

template <class S>
using V7 = Eigen::Matrix<S, 7, 1>;
template <class S>
using V6 = Eigen::Matrix<S, 6, 1>;

/// g(q), G = ∂g/∂q and the convective term c with d²g/dt² = G q'' − c (so G q'' = c); a template
/// on the scalar so that the IDA driver differentiates it exactly (Eigen's AutoDiffScalar).
template <class S>
void constraints(const V7<S>& q, const V7<S>& v, V6<S>& g, Eigen::Matrix<S, 6, 7>& G, V6<S>& c) {
  using std::cos;
  using std::sin;
  constexpr std::array<int, 7> b{1, 0, 0, 0, 0, 0, 0}, bt{1, 1, 0, 0, 0, 0, 0}, ga{0, 0, 1, 0, 0, 0, 0},
      pd{0, 0, 0, 1, 1, 0, 0}, de{0, 0, 0, 0, 1, 0, 0}, oe{0, 0, 0, 0, 0, 1, 1}, ep{0, 0, 0, 0, 0, 0, 1};
  // E reached through K1–K2 equals E reached through K3, through K4–K5 and through K6–K7 (§1.3).
  const std::array<std::array<Term, 4>, 6> loops{{
      {{{rr, true, b}, {-d, true, bt}, {-ss, false, ga}, {0, true, b}}},
      {{{rr, false, b}, {-d, false, bt}, {ss, true, ga}, {0, true, b}}},
      {{{rr, true, b}, {-d, true, bt}, {-e, false, pd}, {-zt, true, de}}},
      {{{rr, false, b}, {-d, false, bt}, {e, true, pd}, {-zt, false, de}}},
      {{{rr, true, b}, {-d, true, bt}, {-zf, true, oe}, {-u, false, ep}}},
      {{{rr, false, b}, {-d, false, bt}, {-zf, false, oe}, {u, true, ep}}},
  }};
  const std::array<double, 6> constant{xb, yb, xa, ya, xa, ya};
  for (int i = 0; i < 6; ++i) {
    g[i] = S(-constant[static_cast<size_t>(i)]);
    c[i] = S(0.0);
    for (int k = 0; k < 7; ++k) G(i, k) = S(0.0);
    for (const Term& t : loops[static_cast<size_t>(i)]) {
      if (t.coef == 0.0) continue;
      S ph(0.0), phd(0.0);
      for (int k = 0; k < 7; ++k)
        if (t.P[static_cast<size_t>(k)]) {
          ph += q[k];
          phd += v[k];
        }
      const S tr = t.cosine ? S(cos(ph)) : S(sin(ph));
      const S dtr = t.cosine ? S(-sin(ph)) : S(cos(ph));
      g[i] += t.coef * tr;
      for (int k = 0; k < 7; ++k)
        if (t.P[static_cast<size_t>(k)]) G(i, k) += t.coef * dtr;
      c[i] += t.coef * tr * phd * phd;  // −d²(trig)/dφ² = trig
    }
  }
}

/// Mass matrix M(q) and force vector f(q, q') of andrews.md §1.3 (spring on K3 included); a
/// template on the scalar like constraints().
template <class S>
void mass_force(const V7<S>& q, const V7<S>& v, Eigen::Matrix<S, 7, 7>& M, V7<S>& f) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const S Th = q[1], ga = q[2], Ph = q[3], Om = q[5];
  const S bep = v[0], thp = v[1], php = v[3], dep = v[4], omp = v[5], epp = v[6];
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) M(i, j) = S(0.0);
  M(0, 0) = m1 * ra * ra + m2 * (rr * rr - 2 * da * rr * cos(Th) + da * da) + I1 + I2;
  M(1, 0) = m2 * (da * da - da * rr * cos(Th)) + I2;
  M(1, 1) = m2 * da * da + I2;
  M(2, 2) = m3 * (sa * sa + sb * sb) + I3;
  M(3, 3) = m4 * (e - ea) * (e - ea) + I4;
  M(4, 3) = m4 * ((e - ea) * (e - ea) + zt * (e - ea) * sin(Ph)) + I4;
  M(4, 4) = m4 * (zt * zt + 2 * zt * (e - ea) * sin(Ph) + (e - ea) * (e - ea)) + m5 * (ta * ta + tb * tb) + I4 + I5;
  M(5, 5) = m6 * (zf - fa) * (zf - fa) + I6;
  M(6, 5) = m6 * ((zf - fa) * (zf - fa) - u * (zf - fa) * sin(Om)) + I6;
  M(6, 6) = m6 * ((zf - fa) * (zf - fa) - 2 * u * (zf - fa) * sin(Om) + u * u) + m7 * (ua * ua + ub * ub) + I6 + I7;
  M(0, 1) = M(1, 0);
  M(3, 4) = M(4, 3);
  M(5, 6) = M(6, 5);
  const S xd = sd * cos(ga) + sc * sin(ga) + xb, yd = sd * sin(ga) - sc * cos(ga) + yb;  // spring point D
  const S L = sqrt((xd - xc) * (xd - xc) + (yd - yc) * (yd - yc));
  const S Fx = -c0 * (L - l0) / L * (xd - xc), Fy = -c0 * (L - l0) / L * (yd - yc);
  f[0] = mom - m2 * da * rr * thp * (thp + 2 * bep) * sin(Th);
  f[1] = m2 * da * rr * bep * bep * sin(Th);
  f[2] = Fx * (sc * cos(ga) - sd * sin(ga)) + Fy * (sd * cos(ga) + sc * sin(ga));
  f[3] = m4 * zt * (e - ea) * dep * dep * cos(Ph);
  f[4] = -m4 * zt * (e - ea) * php * (php + 2 * dep) * cos(Ph);
  f[5] = -m6 * u * (zf - fa) * epp * epp * cos(Om);
  f[6] = m6 * u * (zf - fa) * omp * (omp + 2 * epp) * cos(Om);
}

/// q'' and λ from the index-1 system [[M, Gᵀ], [G, 0]] [q''; λ] = [f; c].
inline void accelerations(const Vec7& q, const Vec7& v, Vec7& qdd, Vec6& lambda) {
  Mat7 M;
  Vec7 f;
  Vec6 g, c;
  Mat67 G;
  mass_force<double>(q, v, M, f);
  constraints<double>(q, v, g, G, c);
  Eigen::Matrix<double, 13, 13> A = Eigen::Matrix<double, 13, 13>::Zero();
  A.topLeftCorner<7, 7>() = M;
  A.topRightCorner<7, 6>() = G.transpose();
  A.bottomLeftCorner<6, 7>() = G;
  Eigen::Matrix<double, 13, 1> rhs;
  rhs << f, c;
  const Eigen::Matrix<double, 13, 1> x = A.partialPivLu().solve(rhs);
  qdd = x.head<7>();
  lambda = x.tail<6>();
}

}  // namespace alphaflex::study::andrews
