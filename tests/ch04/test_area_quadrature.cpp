// Chapter 4: the areas of spheres and disks against an independent numerical
// evaluation of the surface-of-revolution integral,
//
//     A = phiMax * integral of rho(t) * sqrt(rho'(t)^2 + z'(t)^2) dt,
//
// by adaptive Gauss-Kronrod quadrature in double precision (area_oracles.h).
// The test knows the profile of each shape and its derivatives, nothing of
// the algebra that turns the integral into a closed form. The integrator
// itself is checked on polynomials and on a torus, whose area follows from
// Pappus's theorem.
//
// The tests that call Area() are public tests of the chapter's exercises
// (suites Ex4_9_* for the sphere, Ex4_10_* for the disk); the tests of the
// integrator and of its power to reject wrong formulas call no Area() and
// belong to no exercise.

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"

#include "area_oracles.h"
#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace lrt;

namespace {

// Number of random spheres and of random disks.
constexpr int kQuadratureCases = 2000;
// Relative tolerance the adaptive integrator works to.
constexpr double kQuadratureRelTol = 1e-13;
// Relative error allowed to Area(): a few roundings in Float (the shape's
// own computation and the conversion of phiMax to radians), plus the
// integrator's tolerance.
constexpr double kAreaRelTol = 16 * double(MachineEpsilon);
constexpr double kTotalRelTol = kAreaRelTol + 2 * kQuadratureRelTol;

constexpr double kPi = 3.14159265358979323846;

using Integrand = area_oracles::Integrand<double>;
using Integral = area_oracles::Integral<double>;
using Profile = area_oracles::Profile<double>;
using ProfilePoint = area_oracles::ProfilePoint<double>;
using area_oracles::GaussKronrod15;

Integral Integrate(const Integrand &f, double a, double b) {
    return area_oracles::Integrate<double>(f, a, b, kQuadratureRelTol);
}

Integral RevolutionArea(const Profile &profile, double t0, double t1,
                        double phiMax) {
    return area_oracles::RevolutionArea<double>(profile, t0, t1, phiMax,
                                                kQuadratureRelTol);
}

Profile SphereGraphProfile(double r) {
    return area_oracles::SphereGraphProfile<double>(r);
}
Profile SpherePolarProfile(double r) {
    return area_oracles::SpherePolarProfile<double>(r);
}
Profile DiskProfile(double h) { return area_oracles::DiskProfile<double>(h); }
Profile TorusProfile(double R, double r) {
    return area_oracles::TorusProfile<double>(R, r);
}

double RelativeDifference(double a, double b) {
    return std::abs(a - b) / std::abs(b);
}

// Random shape parameters, as Float values that the shape stores exactly.
struct SphereParams {
    Float radius, zMin, zMax, phiMaxDegrees;
};

struct DiskParams {
    Float height, radius, innerRadius, phiMaxDegrees;
};

class ShapeSampler {
  public:
    explicit ShapeSampler(uint64_t seed) : rng(seed) {}
    double Uniform(double a, double b) {
        return std::uniform_real_distribution<double>(a, b)(rng);
    }
    Float LogUniform(double a, double b) {
        return Float(std::exp(Uniform(std::log(a), std::log(b))));
    }
    Float PhiMaxDegrees() {
        // One case in ten is a full turn, which the shapes special-case.
        if (Uniform(0, 1) < 0.1) return 360;
        return Float(Uniform(1, 360));
    }
    SphereParams Sphere() {
        Float r = LogUniform(0.05, 20);
        Float z0, z1;
        do {
            z0 = Float(Uniform(-1, 1) * r);
            z1 = Float(Uniform(-1, 1) * r);
            // Include the poles on purpose: there the profile's slope is
            // infinite and the integral improper.
            if (Uniform(0, 1) < 0.15) z0 = -r;
            if (Uniform(0, 1) < 0.15) z1 = r;
        } while (!(std::abs(double(z1) - double(z0)) > 1e-3 * r));
        return {r, std::min(z0, z1), std::max(z0, z1), PhiMaxDegrees()};
    }
    DiskParams Disk() {
        Float r = LogUniform(0.05, 20);
        Float ri = (Uniform(0, 1) < 0.2) ? 0 : Float(Uniform(0, 0.98) * r);
        return {Float(Uniform(-5, 5)), r, ri, PhiMaxDegrees()};
    }

  private:
    std::mt19937_64 rng;
};

double ToRadians(Float degrees) { return double(degrees) * kPi / 180; }

// The exact area of the stored sphere by quadrature of its graph profile.
Integral SphereAreaByGraph(const SphereParams &s) {
    return RevolutionArea(SphereGraphProfile(s.radius), s.zMin, s.zMax,
                          ToRadians(s.phiMaxDegrees));
}

// ... and of its polar-angle profile; theta runs from z = zMax to z = zMin.
Integral SphereAreaByPolarAngle(const SphereParams &s) {
    double r = s.radius;
    double thetaTop = std::acos(std::max(-1.0, std::min(1.0, s.zMax / r)));
    double thetaBottom = std::acos(std::max(-1.0, std::min(1.0, s.zMin / r)));
    return RevolutionArea(SpherePolarProfile(r), thetaTop, thetaBottom,
                          ToRadians(s.phiMaxDegrees));
}

Integral DiskAreaByProfile(const DiskParams &d) {
    return RevolutionArea(DiskProfile(d.height), d.innerRadius, d.radius,
                          ToRadians(d.phiMaxDegrees));
}

std::string Describe(const SphereParams &s) {
    return "sphere r=" + std::to_string(s.radius) +
           " zMin=" + std::to_string(s.zMin) +
           " zMax=" + std::to_string(s.zMax) +
           " phiMax=" + std::to_string(s.phiMaxDegrees);
}

std::string Describe(const DiskParams &d) {
    return "disk r=" + std::to_string(d.radius) +
           " ri=" + std::to_string(d.innerRadius) +
           " phiMax=" + std::to_string(d.phiMaxDegrees);
}

}  // namespace

// The integrator must be exact (to rounding) for polynomials of degree up
// to 22 on any interval, which checks every node and weight.
TEST(AreaQuadrature, IntegratorIsExactForPolynomials) {
    const double a = -0.7, b = 1.9;
    for (int k = 0; k <= 22; ++k) {
        area_oracles::Estimate<double> e = GaussKronrod15<double>(
            [k](double x) { return std::pow(x, k); }, a, b);
        double exact = (std::pow(b, k + 1) - std::pow(a, k + 1)) / (k + 1);
        EXPECT_NEAR(e.value, exact, 1e-14 * std::max(1.0, std::abs(exact)))
            << "degree " << k;
    }
}

// Adaptivity: an integrand with an infinite slope at an end point, like the
// sphere's profile at a pole.
TEST(AreaQuadrature, IntegratorHandlesInfiniteSlopeAtEndPoint) {
    Integral i = Integrate([](double x) { return std::sqrt(x); }, 0, 1);
    EXPECT_TRUE(i.converged);
    EXPECT_NEAR(i.value, 2.0 / 3.0, 1e-12);
}

// Pappus: a circle of radius r whose center is at distance R from the axis
// sweeps a torus of area (2 pi r)(2 pi R). Nothing in chapter 4 derives it.
TEST(AreaQuadrature, IntegratorReproducesTorusArea) {
    const double R = 3.25, r = 1.5;
    Integral a = RevolutionArea(TorusProfile(R, r), 0, 2 * kPi, 2 * kPi);
    EXPECT_TRUE(a.converged);
    EXPECT_LT(RelativeDifference(a.value, 4 * kPi * kPi * R * r),
              2 * kQuadratureRelTol);
}

// The profiles' derivatives, which the integrand uses, must be the
// derivatives of the profiles (checked by central differences).
TEST(AreaQuadrature, ProfileDerivativesMatchFiniteDifferences) {
    const double r = 1.7, h = 1e-6;
    std::vector<std::pair<Profile, std::vector<double>>> cases = {
        {SphereGraphProfile(r), {-1.6, -0.9, 0.0, 0.4, 1.5}},
        {SpherePolarProfile(r), {0.1, 0.8, 1.6, 2.5, 3.0}},
        {DiskProfile(0.3), {0.2, 1.0, 2.0}},
        {TorusProfile(3, 1), {0.0, 1.0, 2.0, 4.0}}};
    for (const auto &c : cases)
        for (double t : c.second) {
            ProfilePoint p = c.first(t);
            ProfilePoint lo = c.first(t - h), hi = c.first(t + h);
            EXPECT_NEAR(p.drho, (hi.rho - lo.rho) / (2 * h), 1e-6) << t;
            EXPECT_NEAR(p.dz, (hi.z - lo.z) / (2 * h), 1e-6) << t;
        }
}

EXERCISE_TEST(Ex4_9_SphereQuadrature, MatchesGraphProfileIntegral) {
    ShapeSampler sampler(calls::Seed(0x5eed0401));
    for (int i = 0; i < kQuadratureCases; ++i) {
        SphereParams s = sampler.Sphere();
        Float area = ex::SphereArea(Transform(), false, s.radius, s.zMin,
                                    s.zMax, s.phiMaxDegrees);
        Integral a = SphereAreaByGraph(s);
        ASSERT_TRUE(a.converged) << Describe(s);
        ASSERT_LE(RelativeDifference(area, a.value), kTotalRelTol)
            << Describe(s) << ": Area() " << area << ", quadrature "
            << a.value;
    }
}

EXERCISE_TEST(Ex4_9_SphereQuadrature, MatchesPolarProfileIntegral) {
    ShapeSampler sampler(calls::Seed(0x5eed0402));
    for (int i = 0; i < kQuadratureCases; ++i) {
        SphereParams s = sampler.Sphere();
        Float area = ex::SphereArea(Transform(), false, s.radius, s.zMin,
                                    s.zMax, s.phiMaxDegrees);
        Integral a = SphereAreaByPolarAngle(s);
        ASSERT_TRUE(a.converged) << Describe(s);
        ASSERT_LE(RelativeDifference(area, a.value), kTotalRelTol)
            << Describe(s) << ": Area() " << area << ", quadrature "
            << a.value;
    }
}

EXERCISE_TEST(Ex4_10_DiskQuadrature, MatchesProfileIntegral) {
    ShapeSampler sampler(calls::Seed(0x5eed0403));
    for (int i = 0; i < kQuadratureCases; ++i) {
        DiskParams d = sampler.Disk();
        Float area = ex::DiskArea(Transform(), false, d.height, d.radius,
                                  d.innerRadius, d.phiMaxDegrees);
        Integral a = DiskAreaByProfile(d);
        ASSERT_TRUE(a.converged) << Describe(d);
        ASSERT_LE(RelativeDifference(area, a.value), kTotalRelTol)
            << Describe(d) << ": Area() " << area << ", quadrature "
            << a.value;
    }
}

// A check that cannot reject a wrong formula is no check: plausible mistakes
// must fail against the same oracle and tolerance.
TEST(AreaQuadrature, RejectsWrongFormulas) {
    // A hemisphere of radius 2.5: the right area is 2 pi r^2.
    SphereParams hemi{2.5, 0, 2.5, 360};
    double right = SphereAreaByGraph(hemi).value;
    double r = hemi.radius, phi = 2 * kPi;
    std::vector<std::pair<std::string, double>> wrong = {
        {"2 pi r", 2 * kPi * r},
        {"4 pi r^2 (whole sphere)", 4 * kPi * r * r},
        // Thin cylinders without the slope factor: phiMax * int f dz.
        {"phiMax int f dz", phi * kPi * r * r / 4},
        // Proportional to the polar angle range (here pi/2).
        {"phiMax r^2 (thetaMin - thetaMax)", phi * r * r * kPi / 2}};
    for (const auto &w : wrong)
        EXPECT_GT(RelativeDifference(w.second, right), kTotalRelTol)
            << w.first << " was not rejected";
    EXPECT_LE(RelativeDifference(2 * kPi * r * r, right), kTotalRelTol);

    // A band of a partial sphere, away from the poles.
    SphereParams band{1.75, -0.5, 1.25, 270};
    double bandArea = SphereAreaByGraph(band).value;
    double rb = band.radius, phib = ToRadians(band.phiMaxDegrees);
    auto segment = [rb](double z) {  // int sqrt(r^2 - z^2) dz
        return 0.5 * (z * std::sqrt(rb * rb - z * z) +
                      rb * rb * std::asin(z / rb));
    };
    double flatBand = phib * (segment(band.zMax) - segment(band.zMin));
    double thetaBand = phib * rb * rb *
                       (std::acos(band.zMin / rb) - std::acos(band.zMax / rb));
    EXPECT_GT(RelativeDifference(flatBand, bandArea), kTotalRelTol);
    EXPECT_GT(RelativeDifference(thetaBand, bandArea), kTotalRelTol);

    // A full disk of radius 2.5 and a ring.
    double diskArea = DiskAreaByProfile({0, 2.5, 0, 360}).value;
    EXPECT_GT(RelativeDifference(kPi * 2.5, diskArea), kTotalRelTol);
    EXPECT_GT(RelativeDifference(2 * kPi * 2.5 * 2.5, diskArea),
              kTotalRelTol);
    DiskParams ring{0, 2.5, 1.5, 200};
    double ringArea = DiskAreaByProfile(ring).value;
    double phir = ToRadians(ring.phiMaxDegrees);
    EXPECT_GT(RelativeDifference(0.5 * phir * (2.5 - 1.5) * (2.5 - 1.5),
                                 ringArea),
              kTotalRelTol);
    EXPECT_GT(RelativeDifference(phir * (2.5 * 2.5 - 1.5 * 1.5), ringArea),
              kTotalRelTol);
}
