// Constitutive models of mpm2grid (docs/methods/mpm2grid.md, "Continuum model"): the rotation SVD,
// Hencky elasticity, the Drucker-Prager return mapping with saturation-dependent cohesion and
// volume correction, and the weakly compressible water. Every material test runs for Dim = 2
// and Dim = 3.
//
// Tolerances: "eps" below is double precision's unit round-off, 2.2e-16. A Jacobi SVD of a
// 2x2/3x3 matrix reconstructs it to a few eps relative (backward stable), so quantities that go
// through one SVD are checked to 1e-12 relative (about 5000 eps, room for log/exp and the
// condition of the computed quantity); exact algebraic identities (no SVD) to 1e-14.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>  // AngleAxis
#include <Eigen/LU>        // inverse()
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"
#include "solvers/mpm2grid/materials/drucker_prager_return.hpp"
#include "solvers/mpm2grid/materials/hencky_drucker_prager.hpp"
#include "solvers/mpm2grid/materials/log_stretch.hpp"
#include "solvers/mpm2grid/materials/polar_svd.hpp"
#include "solvers/mpm2grid/materials/weakly_compressible_water.hpp"

namespace suite::mpm2grid {
namespace {

using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;

// A sand-like soil: E = 10 MPa, nu = 0.3, friction angle 30 degrees.
constexpr double kYoung = 1e7;                 // Pa
constexpr double kPoisson = 0.3;               // -
constexpr double kPhi = std::numbers::pi / 6;  // rad
constexpr double kCohesion = 5e3;              // Pa

HenckyDruckerPrager sand(double cohesion = 0, bool volume_correction = true) {
  return HenckyDruckerPrager::from_young(kYoung, kPoisson, kPhi, cohesion, volume_correction);
}

// A random rotation: a 2D angle, or a 3D axis-angle, from a fixed-seed generator.
template <int Dim>
Matrix<Dim> random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  if constexpr (Dim == 2) {
    const double a = std::numbers::pi * u(rng);
    Matrix<2> R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return R;
  } else {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    return Eigen::AngleAxisd(std::numbers::pi * u(rng), axis).toRotationMatrix();
  }
}

// F = R1 diag(exp(eps)) R2^T: an elastic deformation gradient with principal Hencky strain eps.
template <int Dim>
Matrix<Dim> with_strain(const Vector<Dim>& eps, std::mt19937& rng) {
  return random_rotation<Dim>(rng) * eps.array().exp().matrix().asDiagonal() * random_rotation<Dim>(rng).transpose();
}

// Principal strain with trace `tr` and deviator `d * (1, -1, 0...)` direction (|dev| = d sqrt 2).
template <int Dim>
Vector<Dim> strain(double tr, double d) {
  Vector<Dim> e = Vector<Dim>::Constant(tr / Dim);
  e(0) += d;
  e(1) -= d;
  return e;
}

// Principal Hencky strain of F (via the rotation SVD).
template <int Dim>
Vector<Dim> hencky_strain(const Matrix<Dim>& F) {
  return rotation_svd<Dim>(F).sigma.array().log().matrix();
}

double rel_err(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(b), 1e-300);
}

// ---------------------------------------------------------------------------------------------
// Rotation SVD

template <typename T>
class RotationSvdTest : public ::testing::Test {};
TYPED_TEST_SUITE(RotationSvdTest, Dims);

TYPED_TEST(RotationSvdTest, ReconstructsWithRotations) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Matrix<Dim>> cases = {Matrix<Dim>::Identity(), 2.5 * Matrix<Dim>::Identity(), random_rotation<Dim>(rng)};
  for (int k = 0; k < 20; ++k) {
    Matrix<Dim> F = Matrix<Dim>::Identity() + 0.6 * Matrix<Dim>::NullaryExpr([&] { return u(rng); });
    if (F.determinant() < 0) F.col(0) *= -1;  // keep det F > 0 here; inversion is tested below
    cases.push_back(F);
  }
  for (const Matrix<Dim>& F : cases) {
    const RotationSvd<Dim> s = rotation_svd<Dim>(F);
    const Matrix<Dim> I = Matrix<Dim>::Identity();
    // Backward-stable SVD: reconstruction and orthogonality to a few eps; 1e-12 is ~5000 eps.
    EXPECT_LE((s.U * s.sigma.asDiagonal() * s.V.transpose() - F).norm(), 1e-12 * F.norm());
    EXPECT_LE((s.U.transpose() * s.U - I).norm(), 1e-12);
    EXPECT_LE((s.V.transpose() * s.V - I).norm(), 1e-12);
    EXPECT_NEAR(s.U.determinant(), 1.0, 1e-12);
    EXPECT_NEAR(s.V.determinant(), 1.0, 1e-12);
    EXPECT_GT(s.sigma.minCoeff(), 0.0);  // det F > 0 -> all singular values positive
  }
}

TYPED_TEST(RotationSvdTest, InvertedElementPutsTheSignOnTheSmallestValue) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(11);
  Vector<Dim> sv = Vector<Dim>::LinSpaced(Dim, 2.0, 0.5);
  sv(Dim - 1) = -sv(Dim - 1);  // det F < 0
  const Matrix<Dim> F = random_rotation<Dim>(rng) * sv.asDiagonal() * random_rotation<Dim>(rng).transpose();
  const RotationSvd<Dim> s = rotation_svd<Dim>(F);
  EXPECT_LE((s.U * s.sigma.asDiagonal() * s.V.transpose() - F).norm(), 1e-12 * F.norm());  // as above
  EXPECT_NEAR(s.U.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(s.V.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(s.sigma(Dim - 1), -0.5, 1e-12);  // the reflection lands on the smallest value
  for (int i = 0; i + 1 < Dim; ++i) EXPECT_GT(s.sigma(i), 0.0);
}

// Deformation gradients on which the stretch decompositions are compared with the SVD: equal
// stretches (exactly, soil at rest, and to 1e-9 and 1e-6, where eigenvectors are ill-defined but
// U (.) U^T is not and the 3D closed-form eigenvalues lose half their digits), two equal and one
// apart, apart by about the 3D series' threshold (log_stretch.hpp), strongly anisotropic, nearly
// flat, and random F near and far from a rotation. 2D takes the first and last of each triple.
template <int Dim>
std::vector<Matrix<Dim>> stretch_cases(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Matrix<Dim> R = random_rotation<Dim>(rng), Q = random_rotation<Dim>(rng);
  std::vector<Matrix<Dim>> cases = {Matrix<Dim>::Identity(), 2.5 * Matrix<Dim>::Identity(),
                                    0.98 * Matrix<Dim>::Identity(), R, 1.1 * R};
  const std::vector<std::array<double, 3>> stretches = {
      {1 + 1e-9, 1, 1},        {1, 1 - 1e-6, 1 - 2e-6},   {0.999, 0.999, 0.99}, {1.01, 0.999, 0.999},
      {1 + 2e-5, 1, 1 - 1e-5}, {1 + 3e-5, 1, 1 - 2.5e-5}, {3.0, 1.6, 0.2},      {3.0, 1.0, 1e-3}};
  for (const auto& sv : stretches) {
    Vector<Dim> d;
    for (int i = 0; i < Dim; ++i) d[i] = sv[static_cast<std::size_t>(Dim == 3 || i == 0 ? i : 2)];
    cases.push_back(R * d.asDiagonal() * Q.transpose());
  }
  for (int k = 0; k < 60; ++k) {
    const double size = k < 20 ? 0.6 : k < 40 ? 1e-3 : 1e-7;
    Matrix<Dim> F = Matrix<Dim>::Identity() + size * Matrix<Dim>::NullaryExpr([&] { return u(rng); });
    if (F.determinant() < 0) F.col(0) *= -1;
    cases.push_back(R * F);
  }
  return cases;
}

// left_stretch (closed form in 2D, Eigen's symmetric eigen-solver in 3D) against the SVD: the same
// log-stretches, and U diag(f(log sigma)) U^T (how the Hencky model uses U) the same for a
// function f that tells the stretches apart; U orthonormal; on stretch_cases(). Both are
// backward stable: 1e-12 as above. An inverted F gives NaN log-stretches, as the SVD's negative
// value does.
TYPED_TEST(RotationSvdTest, LeftStretchAgreesWithTheSvd) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(5);
  const std::vector<Matrix<Dim>> cases = stretch_cases<Dim>(rng);
  const Matrix<Dim> R = random_rotation<Dim>(rng);
  const auto f = [](const Vector<Dim>& e) { return Vector<Dim>((2 * e.array() + 0.7 * e.sum()).matrix()); };
  for (const Matrix<Dim>& F : cases) {
    const RotationSvd<Dim> svd = rotation_svd<Dim>(F);
    const LeftStretch<Dim> s = left_stretch<Dim>(F);
    const Vector<Dim> log_svd = svd.sigma.array().log().matrix();
    std::vector<double> a(log_svd.data(), log_svd.data() + Dim), b(s.log_sigma.data(), s.log_sigma.data() + Dim);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    for (int i = 0; i < Dim; ++i) EXPECT_NEAR(b[i], a[i], 1e-12) << F;
    EXPECT_LE((s.U.transpose() * s.U - Matrix<Dim>::Identity()).norm(), 1e-12);
    const Matrix<Dim> A = svd.U * f(log_svd).asDiagonal() * svd.U.transpose();
    const Matrix<Dim> B = s.U * f(s.log_sigma).asDiagonal() * s.U.transpose();
    EXPECT_LE((A - B).norm(), 1e-12 * std::max(1.0, A.norm())) << F;
  }
  Matrix<Dim> inverted = R;
  inverted.col(0) *= -1;
  EXPECT_TRUE(left_stretch<Dim>(inverted).log_sigma.hasNaN());
}

// The Hencky strain from the eigenvalues of F F^T alone (log_stretch.hpp) against the SVD's
// U diag(log sigma) U^T on stretch_cases(). Round-off of |log V|: 1e-12.
TYPED_TEST(RotationSvdTest, LogStretchAgreesWithTheSvd) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(9);
  const std::vector<Matrix<Dim>> cases = stretch_cases<Dim>(rng);
  const Matrix<Dim> R = random_rotation<Dim>(rng), Q = random_rotation<Dim>(rng);
  const auto deviator = [](const Vector<Dim>& e) { return (e.array() - e.mean()).matrix().norm(); };
  for (const Matrix<Dim>& F : cases) {
    const RotationSvd<Dim> svd = rotation_svd<Dim>(F);
    const Vector<Dim> log_svd = svd.sigma.array().log().matrix();
    const Matrix<Dim> expected = svd.U * log_svd.asDiagonal() * svd.U.transpose();
    const StretchSpectrum<Dim> s = stretch_spectrum<Dim>(F);
    EXPECT_TRUE(s.accurate) << F;
    EXPECT_LE((log_left_stretch<Dim>(s) - expected).norm(), 1e-12 * std::max(1.0, expected.norm())) << F;
    // The principal log-stretches, descending: where two meet, the 3D closed form's single values
    // are off by about sqrt(machine epsilon) times the deviator (measured 4e-10 here), but not
    // what the yield test reads, their sum (log det F) and the norm of their deviator (its error
    // is that one times the gap between them).
    for (int i = 0; i < Dim; ++i)
      EXPECT_NEAR(s.log_sigma[i], log_svd[i], (Dim == 2 ? 1e-12 : 1e-9) * std::max(1.0, std::abs(log_svd[i]))) << F;
    EXPECT_NEAR(s.log_sigma.sum(), std::log(F.determinant()), 1e-13);
    EXPECT_NEAR(deviator(s.log_sigma), deviator(log_svd), 1e-12 * std::max(1.0, log_svd.norm())) << F;
  }
  Matrix<Dim> inverted = R;
  inverted.col(0) *= -1;
  EXPECT_TRUE(stretch_spectrum<Dim>(inverted).log_sigma.hasNaN());
  if constexpr (Dim == 3) {
    // Two stretches of 0.015 and 0.01 against one of 3: the closed form's log V would be off
    // by 8e-9 (it says so), and the Kirchhoff stress comes from the eigen-solver, equal to the
    // SVD's P F^T (log stretches down to -4.6: 1e-11 of (2 mu + 3 lambda) 4.6).
    const Matrix<3> flat = R * Vector<3>(3.0, 0.015, 0.01).asDiagonal() * Q.transpose();
    EXPECT_FALSE(stretch_spectrum<3>(flat).accurate);
    const HenckyDruckerPrager m = HenckyDruckerPrager::from_young(1e6, 0.3, 0.5, 0);
    const Matrix<3> expected = m.first_piola<3>(flat) * flat.transpose();
    EXPECT_LE((m.kirchhoff<3>(flat) - expected).norm(), 1e-11 * (2 * m.mu + 3 * m.lambda) * 4.6);
  }
}

// ---------------------------------------------------------------------------------------------
// Hencky elasticity

template <typename T>
class HenckyTest : public ::testing::Test {};
TYPED_TEST_SUITE(HenckyTest, Dims);

TYPED_TEST(HenckyTest, LameParametersAndWaveSpeed) {
  constexpr int Dim = TypeParam::value;
  const HenckyDruckerPrager m = sand();
  // Textbook conversions; each is a few floating-point operations, so 1e-14 relative.
  EXPECT_LE(rel_err(m.mu, kYoung / (2 * (1 + kPoisson))), 1e-14);
  EXPECT_LE(rel_err(m.lambda, kYoung * kPoisson / ((1 + kPoisson) * (1 - 2 * kPoisson))), 1e-14);
  const double K = Dim == 3 ? kYoung / (3 * (1 - 2 * kPoisson))                    // 3D bulk modulus
                            : kYoung / (2 * (1 + kPoisson) * (1 - 2 * kPoisson));  // plane strain: lambda + mu
  EXPECT_LE(rel_err(m.template bulk_modulus<Dim>(), K), 1e-14);
  // P-wave modulus lambda + 2 mu = E (1 - nu) / ((1 + nu)(1 - 2 nu)).
  const double rho = 2000;
  EXPECT_LE(
      rel_err(m.p_wave_speed(rho), std::sqrt(kYoung * (1 - kPoisson) / ((1 + kPoisson) * (1 - 2 * kPoisson)) / rho)),
      1e-14);
}

TYPED_TEST(HenckyTest, PureDilationGivesIsotropicKirchhoffStress) {
  constexpr int Dim = TypeParam::value;
  const HenckyDruckerPrager m = sand();
  const double stiffness = 2 * m.mu + Dim * m.lambda;  // Pa
  for (double a : {0.8, 1.0, 1.25}) {
    const Matrix<Dim> tau = m.template kirchhoff<Dim>(a * Matrix<Dim>::Identity());
    const Matrix<Dim> expected = stiffness * std::log(a) * Matrix<Dim>::Identity();
    // The SVD of a multiple of I is exact (no Jacobi rotation is needed); what is left is the
    // rounding of log and of the sums: a few eps of the stiffness.
    EXPECT_LE((tau - expected).norm(), 1e-14 * stiffness) << "a = " << a;
  }
}

TYPED_TEST(HenckyTest, FirstPiolaIsTheEnergyDerivative) {
  constexpr int Dim = TypeParam::value;
  const HenckyDruckerPrager m = sand();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 5; ++k) {
    const Matrix<Dim> F = with_strain<Dim>(Vector<Dim>::NullaryExpr([&] { return 0.2 * u(rng); }), rng);
    const Matrix<Dim> P = m.template first_piola<Dim>(F);
    // Central differences of psi, step h = 1e-6 on entries of size ~1: truncation
    // h^2/6 |psi'''| ~ 1e-12 E and round-off eps |psi| / h ~ 2e-10 |psi| are both below 1e-9 of |P|
    // (|P| ~ E |eps| ~ 1e6 Pa, |psi| ~ E |eps|^2 ~ 1e5 J/m^3); tolerance 1e-7 |P|.
    const double h = 1e-6;
    Matrix<Dim> fd;
    for (int i = 0; i < Dim; ++i)
      for (int j = 0; j < Dim; ++j) {
        Matrix<Dim> Fp = F, Fm = F;
        Fp(i, j) += h;
        Fm(i, j) -= h;
        fd(i, j) = (m.template energy_density<Dim>(Fp) - m.template energy_density<Dim>(Fm)) / (2 * h);
      }
    EXPECT_LE((P - fd).norm(), 1e-7 * P.norm());
    // P = tau F^-T exactly in exact arithmetic; both go through one SVD: 1e-12 relative.
    const Matrix<Dim> tau = m.template kirchhoff<Dim>(F);
    EXPECT_LE((P - tau * F.inverse().transpose()).norm(), 1e-12 * P.norm());
    // Energy formula on the principal strain (SVD round-off only): 1e-12 relative.
    const Vector<Dim> eps = hencky_strain<Dim>(F);
    const double psi = m.mu * eps.squaredNorm() + 0.5 * m.lambda * eps.sum() * eps.sum();
    EXPECT_LE(rel_err(m.template energy_density<Dim>(F), psi), 1e-12);
  }
}

TYPED_TEST(HenckyTest, KirchhoffStressIsObjective) {
  constexpr int Dim = TypeParam::value;
  const HenckyDruckerPrager m = sand();
  std::mt19937 rng(5);
  const Matrix<Dim> F = with_strain<Dim>(strain<Dim>(-0.05, 0.03), rng);
  const Matrix<Dim> R = random_rotation<Dim>(rng);
  const Matrix<Dim> tau = m.template kirchhoff<Dim>(F);
  // tau(R F) = R tau(F) R^T; two SVDs of matrices with the same singular values: 1e-12 relative.
  EXPECT_LE((m.template kirchhoff<Dim>(R * F) - R * tau * R.transpose()).norm(), 1e-12 * tau.norm());
}

// ---------------------------------------------------------------------------------------------
// Drucker-Prager return mapping

template <typename T>
class DruckerPragerTest : public ::testing::Test {};
TYPED_TEST_SUITE(DruckerPragerTest, Dims);

TYPED_TEST(DruckerPragerTest, ElasticStateIsUnchanged) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(13);
  for (double c : {0.0, kCohesion}) {
    const HenckyDruckerPrager m = sand(c);
    // Compression tr eps = -0.01 (p = K 0.01 ~ 1e5 Pa) with a small shear: q ~ 2 mu sqrt(3/2)
    // sqrt(2) 1e-3 ~ 1.3e4 Pa, far inside M p ~ 1.1e5 Pa.
    const Matrix<Dim> F = with_strain<Dim>(strain<Dim>(-0.01, 1e-3), rng);
    const ReturnResult<Dim> r = m.template project<Dim>(F, 0.0, 0.0);
    EXPECT_EQ(r.kind, ReturnCase::elastic);
    EXPECT_TRUE(r.F == F);  // bitwise: an elastic return hands F_trial back untouched
    EXPECT_EQ(r.log_jp, 0.0);
    EXPECT_EQ(r.plastic_strain, 0.0);
  }
}

// project_all (four particles at a time, their spectra and strain tensors stage by stage)
// gives each particle bit for bit what project() gives it alone: elastic, cone and apex returns,
// a stored volume correction, a state whose closed-form spectrum is not accurate (3D), and the
// identity the particle update fills its last batch with.
TYPED_TEST(DruckerPragerTest, ProjectAllEqualsProjectOneByOne) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(23);
  const HenckyDruckerPrager m = sand(kCohesion);
  std::vector<Matrix<Dim>> F;
  std::vector<double> log_jp, saturation;
  const auto add = [&](const Matrix<Dim>& f, double jp, double s) {
    F.push_back(f), log_jp.push_back(jp), saturation.push_back(s);
  };
  add(with_strain<Dim>(strain<Dim>(-0.01, 1e-3), rng), 0.0, 0.0);   // elastic
  add(with_strain<Dim>(strain<Dim>(-0.01, 0.2), rng), 0.0, 0.5);    // cone
  add(with_strain<Dim>(strain<Dim>(0.05, 0.0), rng), 0.0, 1.0);     // apex
  add(with_strain<Dim>(strain<Dim>(-0.01, 1e-3), rng), 0.02, 0.3);  // elastic with a shift
  add(Matrix<Dim>::Identity(), 0.0, 0.0);
  if constexpr (Dim == 3) add(random_rotation<3>(rng) * Vector<3>(3.0, 0.015, 0.01).asDiagonal(), 0.0, 0.0);
  // Then random states: every other one compressed by 1% with a shear under 1e-4 (elastic),
  // the rest with strains up to 0.03 and 0.09 (mostly plastic).
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  while (F.size() % 4 != 0 || F.size() < 16) {
    const bool small = F.size() % 2 == 0;
    Matrix<Dim> f = (small ? 0.99 : 1.0) * Matrix<Dim>::Identity();
    for (int i = 0; i < Dim; ++i)
      for (int j = 0; j < Dim; ++j) f(i, j) += u(rng) * (small ? 3e-3 : i == j ? 1.0 : 3.0);
    add(f, F.size() % 3 == 0 ? u(rng) : 0.0, 0.5 + 10 * u(rng));
  }
  int kinds[3] = {0, 0, 0};
  for (std::size_t first = 0; first < F.size(); first += 4) {
    ReturnResult<Dim> batch[4];
    m.template project_all<Dim, 4>(&F[first], &log_jp[first], &saturation[first], batch);
    for (std::size_t n = 0; n < 4; ++n) {
      const ReturnResult<Dim> alone = m.template project<Dim>(F[first + n], log_jp[first + n], saturation[first + n]);
      const ReturnResult<Dim>& b = batch[n];
      SCOPED_TRACE(first + n);
      EXPECT_TRUE(b.F == alone.F);
      EXPECT_TRUE(b.stress == alone.stress);
      EXPECT_EQ(b.log_jp, alone.log_jp);
      EXPECT_EQ(b.kind, alone.kind);
      EXPECT_EQ(b.plastic_strain, alone.plastic_strain);
      EXPECT_EQ(b.has_stress, alone.has_stress);
      ++kinds[static_cast<int>(alone.kind)];
    }
  }
  EXPECT_GT(kinds[static_cast<int>(ReturnCase::elastic)], 4);
  EXPECT_GT(kinds[static_cast<int>(ReturnCase::cone)], 0);
  EXPECT_GT(kinds[static_cast<int>(ReturnCase::apex)], 0);
}

TYPED_TEST(DruckerPragerTest, ShearFarOutsideReturnsExactlyOntoTheCone) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(17);
  for (double c : {0.0, kCohesion})
    for (double S : {0.0, 0.3}) {
      const HenckyDruckerPrager m = sand(c);
      const double M = m.template friction_slope<Dim>(), q_c = m.template cohesion_intercept<Dim>(S);
      const Vector<Dim> eps_tr = strain<Dim>(-0.01, 0.2);  // q_tr ~ 2.6e6 Pa >> M p ~ 1.1e5 Pa
      const Matrix<Dim> F = with_strain<Dim>(eps_tr, rng);
      const ReturnResult<Dim> r = m.template project<Dim>(F, 0.0, S);
      ASSERT_EQ(r.kind, ReturnCase::cone);
      // Strain route: invariants of the returned F_E's Hencky strain. The SVD's relative error
      // in the strain is ~eps / |eps| ~ 1e-14; 1e-10 relative (the requirement) is safe.
      const Vector<Dim> eps = hencky_strain<Dim>(r.F);
      const StressInvariants s = m.template invariants<Dim>(eps);
      EXPECT_LE(rel_err(s.q, M * s.p + q_c), 1e-10);
      // Stress route, independent of the strain formulas: p, q of the Kirchhoff stress.
      const StressInvariants st = kirchhoff_invariants<Dim>(m.template kirchhoff<Dim>(r.F));
      EXPECT_LE(rel_err(st.q, M * st.p + q_c), 1e-10);
      // Zero dilatancy: the volume (tr eps, log det F_E) is unchanged. Absolute in log strain:
      // SVD round-off ~ 1e-15; 1e-12.
      EXPECT_NEAR(eps.sum(), eps_tr.sum(), 1e-12);
      EXPECT_NEAR(std::log(r.F.determinant()), std::log(F.determinant()), 1e-12);
      // Radial return keeps the principal directions: F_new F_tr^-1 = U exp(eps_new - eps_tr) U^T
      // is symmetric (1e-12: one SVD).
      const Matrix<Dim> A = r.F * F.inverse();
      EXPECT_LE((A - A.transpose()).norm(), 1e-12 * A.norm());
      EXPECT_EQ(r.log_jp, 0.0);  // nothing stored: the cone return keeps the volume
      EXPECT_GT(r.plastic_strain, 0.0);
    }
}

// The rate-dependent friction (mu(I)): a cone return at step dt lands on the cone of the angle
// atan(mu(I)) with I from the shear strain the return removed, I = sqrt(2) Delta / dt d /
// sqrt(p / rho_s) (the defining equation, checked on the returned strain to 1e-10 relative);
// faster straining gives a larger q, between the static cone's and the phi_2 cone's; dt = 0 and
// tension (p <= 0) keep the static cone.
TYPED_TEST(DruckerPragerTest, InertialFrictionReturnsOntoTheConeOfItsRate) {
  constexpr int Dim = TypeParam::value;
  for (double c : {0.0, kCohesion}) {
    HenckyDruckerPrager m = sand(c);
    const HenckyDruckerPrager rate_independent = m;
    const double phi_2 = 40 * std::numbers::pi / 180, I0 = 0.279, d = 0.5e-3, rho_s = 2650;
    m.set_inertial_friction(phi_2, I0, d, rho_s);
    const double q_c = m.template cohesion_intercept<Dim>(0.0);
    const Vector<Dim> eps_tr = strain<Dim>(-1e-3, 2e-3);  // p ~ 8.3e3 Pa, q_tr well outside the static cone
    const double p = m.template invariants<Dim>(eps_tr).p;
    double previous = m.template invariants<Dim>(rate_independent.template return_strain<Dim>(eps_tr, 0.0).eps).q;
    const double M_2 = HenckyDruckerPrager::slope_of_sine<Dim>(std::sin(phi_2));
    for (double dt : {1e-1, 1e-3, 1e-5, 1e-7, 1e-9}) {
      const StrainReturn<Dim> r = m.template return_strain<Dim>(eps_tr, 0.0, dt);
      ASSERT_EQ(r.kind, ReturnCase::cone);
      const StressInvariants s = m.template invariants<Dim>(r.eps);
      const auto dev_norm = [](const Vector<Dim>& e) { return (e - Vector<Dim>::Constant(e.sum() / Dim)).norm(); };
      const double delta = dev_norm(eps_tr) - dev_norm(r.eps);
      const double I = std::sqrt(2.0) * delta / dt * d / std::sqrt(p / rho_s);
      const double mu_s = std::tan(kPhi), mu = mu_s + (std::tan(phi_2) - mu_s) * I / (I0 + I);
      const double M = HenckyDruckerPrager::slope_of_sine<Dim>(mu / std::sqrt(1 + mu * mu));
      EXPECT_LE(rel_err(s.q, M * p + q_c), 1e-10) << "dt = " << dt << ", c = " << c;
      EXPECT_NEAR(r.eps.sum(), eps_tr.sum(), 1e-15);  // zero dilatancy, as the static return
      EXPECT_GT(s.q, previous) << "dt = " << dt;      // faster: more friction
      EXPECT_LT(s.q, M_2 * p + q_c) << "dt = " << dt;  // never beyond the phi_2 cone
      previous = s.q;
    }
    // At 1e-9 s the rate is huge (the gap to mu_2 falls like I_0 / I, i.e. like dt): the phi_2
    // cone within 1%.
    EXPECT_LE(rel_err(previous, M_2 * p + q_c), 1e-2);
    // dt = 0: the static return, bit for bit.
    EXPECT_TRUE(m.template return_strain<Dim>(eps_tr, 0.0, 0.0).eps ==
                rate_independent.template return_strain<Dim>(eps_tr, 0.0).eps);
  }
  HenckyDruckerPrager m = sand();
  EXPECT_THROW(m.set_inertial_friction(kPhi, 0.279, 0.5e-3, 2650), InputError);  // phi_2 must exceed phi_f
  EXPECT_THROW(m.set_inertial_friction(0.7, 0.0, 0.5e-3, 2650), InputError);
  EXPECT_THROW(m.set_inertial_friction(0.7, 0.279, -1.0, 2650), InputError);
  EXPECT_THROW(m.set_inertial_friction(0.7, 0.279, 0.5e-3, 0.0), InputError);
}

// In 2D the cone is Mohr-Coulomb in the plane: a state returned onto it has
// (s1 - s2) / 2 = p sin(phi_f) + c cos(phi_f) (compression positive), with the scene's phi_f.
TEST(DruckerPrager2D, ConeIsMohrCoulombInThePlane) {
  std::mt19937 rng(5);
  for (double c : {0.0, kCohesion}) {
    const HenckyDruckerPrager m = sand(c);
    const Vector<2> eps_tr = strain<2>(-0.01, 0.2);
    const ReturnResult<2> r = m.template project<2>(with_strain<2>(eps_tr, rng), 0.0, 0.0);
    ASSERT_EQ(r.kind, ReturnCase::cone);
    const Matrix<2> tau = m.template kirchhoff<2>(r.F);
    const Eigen::SelfAdjointEigenSolver<Matrix<2>> principal(tau);
    const double s1 = -principal.eigenvalues()[0], s2 = -principal.eigenvalues()[1];  // compression positive
    const double radius = 0.5 * std::abs(s1 - s2), centre = 0.5 * (s1 + s2);
    const double phi = m.friction_angle;
    EXPECT_NEAR(radius, centre * std::sin(phi) + c * std::cos(phi), 1e-9 * radius) << "c = " << c;
  }
}

TYPED_TEST(DruckerPragerTest, TensionWithoutCohesionGoesToTheApex) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(19);
  const HenckyDruckerPrager m = sand(0.0);
  const Vector<Dim> eps_tr = strain<Dim>(0.05, 0.02);  // pulled apart: p = -K 0.05 < 0
  const Matrix<Dim> F = with_strain<Dim>(eps_tr, rng);
  const ReturnResult<Dim> r = m.template project<Dim>(F, 0.0, 0.0);
  ASSERT_EQ(r.kind, ReturnCase::apex);
  // F_E = U V^T, a rotation: F^T F = I and det F = 1 to SVD round-off (1e-12).
  EXPECT_LE((r.F.transpose() * r.F - Matrix<Dim>::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r.F.determinant(), 1.0, 1e-12);
  // No stress: the strain of a rotation is ~1e-16, times the stiffness ~3e7 Pa; allow
  // 1e-12 of the stiffness.
  EXPECT_LE(m.template kirchhoff<Dim>(r.F).norm(), 1e-12 * (2 * m.mu + Dim * m.lambda));
  // The removed volume is stored: log_jp = tr eps_tr (volume correction on), 1e-12 absolute.
  EXPECT_NEAR(r.log_jp, eps_tr.sum(), 1e-12);
  // Without correction, log_jp passes through untouched.
  EXPECT_EQ(sand(0.0, false).template project<Dim>(F, 0.25, 0.0).log_jp, 0.25);
}

TYPED_TEST(DruckerPragerTest, CohesionHoldsSmallTensionOnlyWhileDry) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(23);
  const HenckyDruckerPrager m = sand(kCohesion);
  const double K = m.template bulk_modulus<Dim>(), M = m.template friction_slope<Dim>();
  const double tr_apex_dry = m.template cohesion_intercept<Dim>(0.0) / (M * K);  // tip of the dry cone, log strain
  // Half-way to the dry tip in tension with a small shear (q = 5% of the dry cone's q there).
  const double tr = 0.5 * tr_apex_dry;
  const double q_allowed = M * (-K * tr) + m.template cohesion_intercept<Dim>(0.0);
  const double d = 0.05 * q_allowed / (2 * m.mu * std::sqrt(1.5) * std::sqrt(2.0));
  const Matrix<Dim> F = with_strain<Dim>(strain<Dim>(tr, d), rng);

  for (double S : {0.0, 0.25, -0.3}) {  // c = c0, 0.75 c0, c0 (S clamped to 0): tip beyond tr
    const ReturnResult<Dim> r = m.template project<Dim>(F, 0.0, S);
    EXPECT_EQ(r.kind, ReturnCase::elastic) << "S = " << S;
    EXPECT_TRUE(r.F == F);
  }
  for (double S : {0.75, 1.0, 1.7}) {  // c = 0.25 c0, 0, 0 (S clamped to 1): tip short of tr
    const ReturnResult<Dim> r = m.template project<Dim>(F, 0.0, S);
    ASSERT_EQ(r.kind, ReturnCase::apex) << "S = " << S;
    const StressInvariants st = kirchhoff_invariants<Dim>(m.template kirchhoff<Dim>(r.F));
    // At the tip: p = -q_c(S) / M and q = 0. Through one SVD, the stresses carry ~1e-16 of the
    // stiffness (~3e7 Pa) as round-off: absolute 1e-12 * stiffness ~ 3e-5 Pa, against q_c ~ 1e4 Pa.
    const double tol = 1e-12 * (2 * m.mu + Dim * m.lambda);
    EXPECT_NEAR(st.p, -m.template cohesion_intercept<Dim>(S) / M, tol) << "S = " << S;
    EXPECT_NEAR(st.q, 0.0, tol) << "S = " << S;
  }
  // Saturation beyond [0, 1] is clamped: the same cohesion as the end of the range.
  EXPECT_EQ(m.cohesion_at(1.7), 0.0);
  EXPECT_EQ(m.cohesion_at(-0.3), kCohesion);
  EXPECT_TRUE(m.template project<Dim>(F, 0.0, 1.7).F == m.template project<Dim>(F, 0.0, 1.0).F);
}

TYPED_TEST(DruckerPragerTest, FrictionlessCohesiveSoilHasNoApex) {
  constexpr int Dim = TypeParam::value;
  // phi_f = 0: M = 0, the surface is the cylinder q <= q_c (2 c in 3D, sqrt(3) c in 2D: Tresca's
  // |s1 - s2| / 2 <= c in the plane); tension is held elastically.
  const HenckyDruckerPrager m = HenckyDruckerPrager::from_young(kYoung, kPoisson, 0.0, kCohesion);
  EXPECT_EQ(m.template friction_slope<Dim>(), 0.0);
  EXPECT_NEAR(m.template cohesion_intercept<Dim>(0.0), (Dim == 2 ? std::sqrt(3.0) : 2.0) * kCohesion, 1e-9);
  const Vector<Dim> tension = strain<Dim>(0.01, 0.0);
  EXPECT_EQ(m.template return_strain<Dim>(tension, 0.0).kind, ReturnCase::elastic);
  const StrainReturn<Dim> r = m.template return_strain<Dim>(strain<Dim>(0.01, 0.1), 0.0);
  ASSERT_EQ(r.kind, ReturnCase::cone);
  // On the cylinder, no SVD involved: 1e-12 relative.
  EXPECT_LE(rel_err(m.template invariants<Dim>(r.eps).q, m.template cohesion_intercept<Dim>(0.0)), 1e-12);
}

TYPED_TEST(DruckerPragerTest, ReturnMappingIsObjective) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(29);
  const HenckyDruckerPrager m = sand(kCohesion);
  const Matrix<Dim> R = random_rotation<Dim>(rng);
  for (const Vector<Dim>& e : {strain<Dim>(-0.01, 0.2), strain<Dim>(0.05, 0.02)}) {
    const Matrix<Dim> F = with_strain<Dim>(e, rng);
    const Matrix<Dim> a = m.template project<Dim>(R * F, 0.0, 0.2).F;
    const Matrix<Dim> b = R * m.template project<Dim>(F, 0.0, 0.2).F;
    EXPECT_LE((a - b).norm(), 1e-12 * b.norm());  // two SVDs: 1e-12 relative
  }
}

TYPED_TEST(DruckerPragerTest, FromYoungRejectsBadParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(HenckyDruckerPrager::from_young(0, 0.3, kPhi, 0), InputError);
  EXPECT_THROW(HenckyDruckerPrager::from_young(nan, 0.3, kPhi, 0), InputError);
  EXPECT_THROW(HenckyDruckerPrager::from_young(kYoung, 0.5, kPhi, 0), InputError);
  EXPECT_THROW(HenckyDruckerPrager::from_young(kYoung, -1.0, kPhi, 0), InputError);
  EXPECT_THROW(HenckyDruckerPrager::from_young(kYoung, 0.3, -0.1, 0), InputError);
  EXPECT_THROW(HenckyDruckerPrager::from_young(kYoung, 0.3, std::numbers::pi / 2, 0), InputError);
  EXPECT_THROW(HenckyDruckerPrager::from_young(kYoung, 0.3, kPhi, -1), InputError);
  EXPECT_NO_THROW(HenckyDruckerPrager::from_young(kYoung, 0.3, 0.0, 0));
}

// ---------------------------------------------------------------------------------------------
// Volume correction. What it promises (see hencky_drucker_prager.hpp): log_jp always equals the
// plastic log-volume log det F - log det F_E, it is >= 0, and it is 0 whenever the particle is
// not at the apex. So sand pulled apart and pushed back to its original volume is again stress-
// free at its original density, and compressing it further loads it like fresh sand. Without
// the correction the apex projections' volume stays in F_P: the same cycle leaves it loaded as if
// its rest volume had grown by exp(Dim * stretch).

template <int Dim>
struct CycleState {
  Matrix<Dim> F_total = Matrix<Dim>::Identity();  // total deformation F = F_E F_P
  Matrix<Dim> F_E = Matrix<Dim>::Identity();
  double log_jp = 0;
  ReturnCase last = ReturnCase::elastic;
};

template <int Dim>
void apply_step(const HenckyDruckerPrager& m, const Matrix<Dim>& increment, CycleState<Dim>& s) {
  s.F_total = increment * s.F_total;
  const ReturnResult<Dim> r = m.template project<Dim>(increment * s.F_E, s.log_jp, 0.0);
  s.F_E = r.F;
  s.log_jp = r.log_jp;
  s.last = r.kind;
}

TYPED_TEST(DruckerPragerTest, VolumeCorrectionStretchCompressCycle) {
  constexpr int Dim = TypeParam::value;
  const Matrix<Dim> I = Matrix<Dim>::Identity();
  const double ds = 0.02;     // log stretch per axis per step
  const int n = 10;           // steps pulling apart: log volume + n ds Dim
  const double extra = 0.01;  // then log strain per axis of compression beyond the start
  CycleState<Dim> with, without;
  const HenckyDruckerPrager corrected = sand(0.0, true), plain = sand(0.0, false);
  auto both = [&](const Matrix<Dim>& inc) {
    apply_step<Dim>(corrected, inc, with);
    apply_step<Dim>(plain, inc, without);
    // The invariant of the correction, every step: log det F = log det F_E + log_jp. Each step
    // adds ~1e-16 of round-off; 1e-12 absolute in log volume.
    EXPECT_NEAR(std::log(with.F_total.determinant()), std::log(with.F_E.determinant()) + with.log_jp, 1e-12);
  };
  for (int k = 0; k < n; ++k) both(std::exp(ds) * I);
  // Pulled apart: both at the apex, stress-free, the volume in log_jp (or lost, without).
  EXPECT_EQ(with.last, ReturnCase::apex);
  EXPECT_NEAR(with.log_jp, n * ds * Dim, 1e-12);  // sum of n exact logs: round-off only
  EXPECT_EQ(without.log_jp, 0.0);
  for (int k = 0; k < n; ++k) both(std::exp(-ds) * I);  // back to the original volume
  // F_total = I again (to round-off); with the correction the stored volume is given back.
  EXPECT_NEAR(with.log_jp, 0.0, 1e-12);
  EXPECT_LE(corrected.template kirchhoff<Dim>(with.F_E).norm(), 1e-12 * (2 * corrected.mu + Dim * corrected.lambda));
  for (int k = 0; k < 5; ++k) both(std::exp(-extra / 5) * I);  // compress beyond the start

  const double stiffness = 2 * corrected.mu + Dim * corrected.lambda;  // tau = stiffness tr/Dim I
  const Matrix<Dim> fresh = corrected.template kirchhoff<Dim>(std::exp(-extra) * I);
  // With correction: loaded exactly like fresh sand compressed by `extra` (1e-12 relative:
  // sums of exact logs and one SVD of a multiple of I).
  EXPECT_EQ(with.last, ReturnCase::elastic);
  EXPECT_LE((corrected.template kirchhoff<Dim>(with.F_E) - fresh).norm(), 1e-12 * fresh.norm());
  EXPECT_NEAR(std::log(with.F_total.determinant()) - std::log(with.F_E.determinant()), 0.0, 1e-12);
  // Without: it has kept the volume gained at the apex, n ds Dim in log volume, and is loaded as
  // if compressed by n ds + extra per axis: (n ds + extra) / extra = 21 times the stress.
  EXPECT_NEAR(std::log(without.F_total.determinant()) - std::log(without.F_E.determinant()), n * ds * Dim, 1e-12);
  const Matrix<Dim> expected_plain = -stiffness * (n * ds + extra) * I;
  EXPECT_LE((plain.template kirchhoff<Dim>(without.F_E) - expected_plain).norm(), 1e-12 * expected_plain.norm());
}

TYPED_TEST(DruckerPragerTest, VolumeCorrectionInvariantOnRandomLoading) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(31);
  std::normal_distribution<double> g(0, 1);
  const Matrix<Dim> I = Matrix<Dim>::Identity();
  CycleState<Dim> with, without;
  const HenckyDruckerPrager corrected = sand(kCohesion, true), plain = sand(kCohesion, false);
  double plastic_without = 0;  // log det F_P without correction, only ever grows
  int apex = 0, cone = 0;
  auto check = [&] {
    apex += with.last == ReturnCase::apex;
    cone += with.last == ReturnCase::cone;
    // The correction's promises, every step (round-off ~1e-16 per step over < 1000 steps; 1e-11).
    EXPECT_NEAR(std::log(with.F_total.determinant()), std::log(with.F_E.determinant()) + with.log_jp, 1e-11);
    EXPECT_GE(with.log_jp, 0.0);
    if (with.last != ReturnCase::apex) {
      EXPECT_EQ(with.log_jp, 0.0);
    }
    // Without: the plastic volume ratchets up (apex projections only ever remove volume from
    // F_E; elastic and cone returns keep it, to round-off: 1e-12).
    const double plastic = std::log(without.F_total.determinant()) - std::log(without.F_E.determinant());
    EXPECT_GE(plastic, plastic_without - 1e-12);
    plastic_without = plastic;
  };
  auto step = [&](const Matrix<Dim>& inc) {
    apply_step<Dim>(corrected, inc, with);
    apply_step<Dim>(plain, inc, without);
    check();
  };
  // Velocity-gradient-like increments I + L: a random traceless shear of 1% per step plus an
  // isotropic volume drift: slight compression (shear reaches the cone), then pulling apart
  // (apex), then pushing back by the same mean amount.
  for (int k = 0; k < 400; ++k) {
    const double vol = (k < 100 ? -2e-4 : k < 250 ? 4e-3 : -4e-3) + 5e-4 * g(rng);
    Matrix<Dim> shear = 0.01 * Matrix<Dim>::NullaryExpr([&] { return g(rng); });
    shear -= (shear.trace() / Dim) * I;
    step(I + shear + vol * I);
  }
  // Finish with isotropic compression until the total volume is 1% (log) below the start: then
  // log det F_E + log_jp < 0 with log_jp >= 0, so the sand is in compression, not at the apex.
  for (int k = 0; k < 1000 && std::log(with.F_total.determinant()) > -0.01 * Dim; ++k) step(std::exp(-2e-3) * I);
  EXPECT_LT(std::log(with.F_total.determinant()), -0.01 * Dim + 1e-12);
  EXPECT_GT(apex, 0);  // the loading did visit the apex...
  EXPECT_GT(cone, 0);  // ...and the cone
  EXPECT_NE(with.last, ReturnCase::apex);
  EXPECT_EQ(with.log_jp, 0.0);       // with correction, back in contact nothing is left over
  EXPECT_GT(plastic_without, 0.05);  // without, the sand keeps > 5% more log volume for good
}

// ---------------------------------------------------------------------------------------------
// Weakly compressible water

template <typename T>
class WaterTest : public ::testing::Test {};
TYPED_TEST_SUITE(WaterTest, Dims);

constexpr double kWaterK = 1e5;  // Pa: a weakly compressible choice (c = sqrt(7e5/1000) = 26 m/s)

TYPED_TEST(WaterTest, PressureVanishesAtRest) {
  constexpr int Dim = TypeParam::value;
  const WeaklyCompressibleWater w = WeaklyCompressibleWater::make(kWaterK);
  EXPECT_EQ(w.pressure(1.0), 0.0);  // 1^-gamma = 1 exactly
  EXPECT_TRUE(w.template kirchhoff<Dim>(1.0).isZero(0.0));
  EXPECT_TRUE(w.template cauchy<Dim>(1.0).isZero(0.0));
}

TYPED_TEST(WaterTest, StiffnessAtRestIsGammaK) {
  const WeaklyCompressibleWater w = WeaklyCompressibleWater::make(kWaterK, 7, -std::numeric_limits<double>::infinity());
  EXPECT_LE(rel_err(-w.pressure_derivative(1.0), 7 * kWaterK), 1e-15);  // one multiplication
  EXPECT_LE(rel_err(w.effective_bulk_modulus(), 7 * kWaterK), 1e-15);
  // Central difference, h = 1e-6: truncation h^2/6 |p'''(1)| = h^2/6 gamma(gamma+1)(gamma+2) k
  // ~ 8e-11 k, round-off eps k / h ~ 2e-10 k, against 7 k: 1e-8 relative.
  const double h = 1e-6;
  const double fd = (w.pressure(1 + h) - w.pressure(1 - h)) / (2 * h);
  EXPECT_LE(rel_err(-fd, 7 * kWaterK), 1e-8);
}

TYPED_TEST(WaterTest, SoundSpeedIsDpDrhoAtRest) {
  const WeaklyCompressibleWater w = WeaklyCompressibleWater::make(kWaterK, 7, -std::numeric_limits<double>::infinity());
  const double rho0 = 1000;
  EXPECT_LE(rel_err(w.sound_speed(rho0), std::sqrt(7 * kWaterK / rho0)), 1e-15);
  // c^2 = dp/drho at rho0 with J = rho0 / rho. Central difference with h = 1e-6 rho0: relative
  // truncation and round-off as in the previous test; 1e-8.
  const double h = 1e-6 * rho0;
  const double dp_drho = (w.pressure(rho0 / (rho0 + h)) - w.pressure(rho0 / (rho0 - h))) / (2 * h);
  EXPECT_LE(rel_err(std::sqrt(dp_drho), w.sound_speed(rho0)), 1e-8);
}

TYPED_TEST(WaterTest, StressesFromPressure) {
  constexpr int Dim = TypeParam::value;
  const WeaklyCompressibleWater w = WeaklyCompressibleWater::make(kWaterK);
  const double J = 0.95;
  const double p = kWaterK * (std::pow(J, -7.0) - 1);  // compressed: p > 0
  const Matrix<Dim> I = Matrix<Dim>::Identity();
  // Same formula and operations: 1e-14 relative.
  EXPECT_LE(rel_err(w.pressure(J), p), 1e-14);
  EXPECT_LE((w.template cauchy<Dim>(J) + p * I).norm(), 1e-14 * p);
  EXPECT_LE((w.template kirchhoff<Dim>(J) + J * p * I).norm(), 1e-14 * p);
}

// J^-gamma by repeated squaring for whole gammas up to 16 against pow: a squaring doubles its
// operand's relative error and adds half an ulp, so J^n carries at most about n/2 ulp, the
// division half one more: (n + 1) / 2 ulp, (n + 1) 1.2e-16 relative. Other gammas go to pow itself.
TEST(Water, InversePowerIsPow) {
  for (int n = 1; n <= 16; ++n) {
    const WeaklyCompressibleWater w = WeaklyCompressibleWater::make(kWaterK, n);
    for (double J = 0.8; J < 1.25; J += 0.0137)
      EXPECT_LE(rel_err(w.inverse_power(J), std::pow(J, -n)), (n + 1) * 1.2e-16) << n << " " << J;
  }
  for (const double gamma : {6.5, 17.0, 1e20}) {
    const WeaklyCompressibleWater w = WeaklyCompressibleWater::make(kWaterK, gamma);
    EXPECT_EQ(w.inverse_power(0.97), std::pow(0.97, -gamma));
  }
}

TYPED_TEST(WaterTest, TensionClamp) {
  constexpr int Dim = TypeParam::value;
  const double J = 1.1, raw = kWaterK * (std::pow(J, -7.0) - 1);  // ~ -4.9e4 Pa: tension
  const double inf = std::numeric_limits<double>::infinity();
  // Default: no tension at all, so no stress.
  const WeaklyCompressibleWater none = WeaklyCompressibleWater::make(kWaterK);
  EXPECT_EQ(none.pressure(J), 0.0);
  EXPECT_TRUE(none.template kirchhoff<Dim>(J).isZero(0.0));
  // A small allowed tension.
  EXPECT_EQ(WeaklyCompressibleWater::make(kWaterK, 7, -1e3).pressure(J), -1e3);
  // Clamp off: the raw law (same operations: 1e-14).
  EXPECT_LE(rel_err(WeaklyCompressibleWater::make(kWaterK, 7, -inf).pressure(J), raw), 1e-14);
  EXPECT_LE(rel_err(none.unclamped_pressure(J), raw), 1e-14);
  // The clamp never touches compression.
  EXPECT_EQ(none.pressure(0.9), none.unclamped_pressure(0.9));
}

TYPED_TEST(WaterTest, MakeRejectsBadParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(WeaklyCompressibleWater::make(0), InputError);
  EXPECT_THROW(WeaklyCompressibleWater::make(nan), InputError);
  EXPECT_THROW(WeaklyCompressibleWater::make(kWaterK, 0), InputError);
  EXPECT_THROW(WeaklyCompressibleWater::make(kWaterK, 7, 1.0), InputError);
  EXPECT_THROW(WeaklyCompressibleWater::make(kWaterK, 7, nan), InputError);
}

}  // namespace
}  // namespace suite::mpm2grid
