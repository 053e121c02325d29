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
// (suites Ex4_9_* for the sphere, Ex4_10_* for the disk, Ex4_12_* for the
// paraboloid); the tests of the integrator and of its power to reject wrong
// formulas call no Area() and belong to no exercise, and those of the
// cylinder, the cone and the hyperboloid call the book's Area().

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/cone.h"
#include "lrt/shapes/paraboloid.h"
#include "lrt/shapes/hyperboloid.h"

#include "area_oracles.h"
#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
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
        {TorusProfile(3, 1), {0.0, 1.0, 2.0, 4.0}},
        {area_oracles::CylinderProfile<double>(1.3), {-1.0, 0.5, 2.0}},
        {area_oracles::ConeProfile<double>(1.3, 2.1), {0.1, 1.0, 2.0}},
        {area_oracles::ParaboloidGraphProfile<double>(1.3, 2.1),
         {0.1, 1.0, 2.0}},
        {area_oracles::ParaboloidRadialProfile<double>(1.3, 2.1),
         {0.0, 0.5, 1.3}},
        {area_oracles::HyperboloidGraphProfile<double>(1, 0.5, -1, -0.3, 1.2,
                                                       2),
         {-0.9, 0.0, 0.7, 1.9}},
        {area_oracles::HyperboloidSegmentProfile<double>(1, 0.5, -1, -0.3,
                                                         1.2, 2),
         {0.1, 0.5, 0.9}}};
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

// ---------------------------------------------------------------------------
// The other quadrics: the cylinder, the cone, the paraboloid and the
// hyperboloid. Each Area() is compared with two integrals that know nothing
// of the sections' closed forms: the nested quadrature of the area element
// |dp/du x dp/dv| of the shape's (u, v) parametrization, and the
// surface-of-revolution integral of its profile. The paraboloid's tests are
// public tests of ex-4.12 (suite Ex4_12_*); the others call the book's
// Area() directly, as no exercise writes it.

namespace {

// Random shapes per kind: the nested quadrature costs some 15 one-dimensional
// integrals per shape.
const int kQuadricCases = calls::Cases(400, 200);

Transform &Identity() {
    static Transform identity;
    return identity;
}

using Surface = area_oracles::Surface<double>;

Integral ParametricArea(const Surface &surface, double vSplit = -1) {
    return area_oracles::ParametricArea<double>(surface, kQuadratureRelTol,
                                                vSplit);
}

struct CylinderParams {
    Float radius, z0, z1, phiMaxDegrees;
};
struct ConeParams {
    Float height, radius, phiMaxDegrees;
};
struct ParaboloidParams {
    Float radius, z0, z1, phiMaxDegrees;
    // The heights the constructor keeps: ordered, clamped below at 0.
    double zMin() const { return std::max(0.0, double(std::min(z0, z1))); }
    double zMax() const { return double(std::max(z0, z1)); }
};
struct HyperboloidParams {
    Point3f p1, p2;
    Float phiMaxDegrees;
};

class QuadricSampler {
  public:
    explicit QuadricSampler(uint64_t seed) : shapes(seed), rng(seed + 1) {}
    double Uniform(double a, double b) {
        return std::uniform_real_distribution<double>(a, b)(rng);
    }
    // Heights in either order: the constructors must not care.
    void MaybeSwap(Float &a, Float &b) {
        if (Uniform(0, 1) < 0.5) std::swap(a, b);
    }
    // Height to width ratios from 1e-3 to 1e3: needles and dishes.
    CylinderParams Cylinder() {
        Float r = shapes.LogUniform(0.01, 100);
        Float z0 = Float(Uniform(-5, 5) * r);
        Float z1 = Float(z0 + r * shapes.LogUniform(1e-3, 1e3));
        MaybeSwap(z0, z1);
        return {r, z0, z1, shapes.PhiMaxDegrees()};
    }
    ConeParams Cone() {
        Float r = shapes.LogUniform(0.01, 100);
        return {Float(r * shapes.LogUniform(1e-3, 1e3)), r,
                shapes.PhiMaxDegrees()};
    }
    ParaboloidParams Paraboloid() {
        Float r = shapes.LogUniform(0.05, 20);
        Float zMax = Float(r * shapes.LogUniform(1e-3, 1e3));
        double c = Uniform(0, 1);
        // With the tip (z0 = 0, or below 0 and clamped), or cut above it.
        Float z0 = c < 0.3 ? 0 : c < 0.4 ? Float(-Uniform(0, 1) * zMax)
                                         : Float(Uniform(0.001, 0.999) * zMax);
        Float z1 = zMax;
        MaybeSwap(z0, z1);
        return {r, z0, z1, shapes.PhiMaxDegrees()};
    }
    // General segments, and on purpose the degenerate ones: vertical
    // (a cylinder), ending on the axis (a cone), crossing the axis (a
    // double cone) and nearly horizontal.
    HyperboloidParams Hyperboloid(int kind) {
        double s = shapes.LogUniform(0.1, 10);
        auto coordinate = [&] { return Float(s * Uniform(-1, 1)); };
        Point3f p1(coordinate(), coordinate(), coordinate());
        Point3f p2(coordinate(), coordinate(), coordinate());
        if (kind == 1) p2.x = p1.x, p2.y = p1.y;
        if (kind == 2) p2.x = 0, p2.y = 0;
        if (kind == 3) {
            Float k = Float(Uniform(0.2, 3));
            p2.x = -k * p1.x, p2.y = -k * p1.y;
        }
        if (kind == 4) p2.z = Float(p1.z + s * 1e-3 * Uniform(0.5, 1));
        if (p1.z == p2.z || (p1.x == 0 && p1.y == 0 && p2.x == 0 && p2.y == 0))
            return Hyperboloid(kind);
        return {p1, p2, shapes.PhiMaxDegrees()};
    }

  private:
    ShapeSampler shapes;
    std::mt19937_64 rng;
};

Integral CylinderByParametrization(const CylinderParams &c) {
    return ParametricArea(area_oracles::CylinderSurface<double>(
        c.radius, c.z0, c.z1, ToRadians(c.phiMaxDegrees)));
}
Integral CylinderByProfile(const CylinderParams &c) {
    return RevolutionArea(area_oracles::CylinderProfile<double>(c.radius),
                          std::min(c.z0, c.z1), std::max(c.z0, c.z1),
                          ToRadians(c.phiMaxDegrees));
}
Integral ConeByParametrization(const ConeParams &c) {
    return ParametricArea(area_oracles::ConeSurface<double>(
        c.radius, c.height, ToRadians(c.phiMaxDegrees)));
}
Integral ConeByProfile(const ConeParams &c) {
    return RevolutionArea(
        area_oracles::ConeProfile<double>(c.radius, c.height), 0, c.height,
        ToRadians(c.phiMaxDegrees));
}
Integral ParaboloidByParametrization(const ParaboloidParams &p) {
    return ParametricArea(area_oracles::ParaboloidSurface<double>(
        p.radius, p.zMin(), p.zMax(), ToRadians(p.phiMaxDegrees)));
}
Integral ParaboloidByGraph(const ParaboloidParams &p) {
    return RevolutionArea(
        area_oracles::ParaboloidGraphProfile<double>(p.radius, p.zMax()),
        p.zMin(), p.zMax(), ToRadians(p.phiMaxDegrees));
}
Integral ParaboloidByRadius(const ParaboloidParams &p) {
    double rhoMin = p.radius * std::sqrt(p.zMin() / p.zMax());
    return RevolutionArea(
        area_oracles::ParaboloidRadialProfile<double>(p.radius, p.zMax()),
        rhoMin, p.radius, ToRadians(p.phiMaxDegrees));
}
// The hyperboloid's integrals in long double: near its waist a nearly
// horizontal segment is nearly tangent to the circles of latitude, and the
// area element's cross product, or the profile's slope, cancels there by
// the ratio of the segment's height to its length (down to 1e-4 here).
Integral ToDouble(const area_oracles::Integral<long double> &i) {
    return {double(i.value), i.converged};
}
Integral HyperboloidByParametrization(const HyperboloidParams &h) {
    using LD = long double;
    const Point3f &a = h.p1, &b = h.p2;
    return ToDouble(area_oracles::ParametricArea<LD>(
        area_oracles::HyperboloidSurface<LD>(a.x, a.y, a.z, b.x, b.y, b.z,
                                             ToRadians(h.phiMaxDegrees)),
        kQuadratureRelTol, area_oracles::NearestToAxis<LD>(a.x, a.y, b.x, b.y)));
}
// The profile by height; split where the segment passes nearest the axis,
// where the profile of a segment that crosses the axis has a corner.
Integral HyperboloidByProfile(const HyperboloidParams &h) {
    using LD = long double;
    const Point3f &a = h.p1, &b = h.p2;
    area_oracles::Profile<LD> profile =
        area_oracles::HyperboloidGraphProfile<LD>(a.x, a.y, a.z, b.x, b.y,
                                                  b.z);
    LD v = area_oracles::NearestToAxis<LD>(a.x, a.y, b.x, b.y);
    LD zLo = std::min(a.z, b.z), zHi = std::max(a.z, b.z);
    LD phi = ToRadians(h.phiMaxDegrees);
    auto area = [&](LD z0, LD z1) {
        return area_oracles::RevolutionArea<LD>(profile, z0, z1, phi,
                                                kQuadratureRelTol);
    };
    if (!(v > 0 && v < 1)) return ToDouble(area(zLo, zHi));
    LD zSplit = LD(a.z) + v * (LD(b.z) - LD(a.z));
    area_oracles::Integral<LD> lo = area(zLo, zSplit), hi = area(zSplit, zHi);
    return {double(lo.value + hi.value), lo.converged && hi.converged};
}

std::string Describe(const CylinderParams &c) {
    return "cylinder r=" + std::to_string(c.radius) + " z=[" +
           std::to_string(c.z0) + ", " + std::to_string(c.z1) +
           "] phiMax=" + std::to_string(c.phiMaxDegrees);
}
std::string Describe(const ConeParams &c) {
    return "cone h=" + std::to_string(c.height) +
           " r=" + std::to_string(c.radius) +
           " phiMax=" + std::to_string(c.phiMaxDegrees);
}
std::string Describe(const ParaboloidParams &p) {
    return "paraboloid r=" + std::to_string(p.radius) + " z=[" +
           std::to_string(p.z0) + ", " + std::to_string(p.z1) +
           "] phiMax=" + std::to_string(p.phiMaxDegrees);
}
std::string Describe(const HyperboloidParams &h) {
    auto point = [](const Point3f &p) {
        return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) +
               ", " + std::to_string(p.z) + ")";
    };
    return "hyperboloid " + point(h.p1) + " -> " + point(h.p2) +
           " phiMax=" + std::to_string(h.phiMaxDegrees);
}

Float Area(const CylinderParams &c) {
    return Cylinder(&Identity(), &Identity(), false, c.radius, c.z0, c.z1,
                    c.phiMaxDegrees).Area();
}
Float Area(const ConeParams &c) {
    return Cone(&Identity(), &Identity(), false, c.height, c.radius,
                c.phiMaxDegrees).Area();
}
Float Area(const HyperboloidParams &h) {
    return Hyperboloid(&Identity(), &Identity(), false, h.p1, h.p2,
                       h.phiMaxDegrees).Area();
}

// Area() against the integrals, which must have converged.
void ExpectMatches(Float area, const std::vector<Integral> &integrals,
                   const std::string &what) {
    for (const Integral &i : integrals) {
        ASSERT_TRUE(i.converged) << what;
        ASSERT_LE(RelativeDifference(area, i.value), kTotalRelTol)
            << what << ": Area() " << area << ", quadrature " << i.value;
    }
}

}  // namespace

// The quadrics' parametrizations: their partial derivatives against central
// differences (their profiles are in the table above).
TEST(AreaQuadrature, QuadricPartialDerivativesMatchFiniteDifferences) {
    const double h = 1e-6;
    std::vector<Surface> surfaces = {
        area_oracles::CylinderSurface<double>(1.3, -0.5, 2, 5),
        area_oracles::ConeSurface<double>(1.3, 2.1, 4),
        area_oracles::ParaboloidSurface<double>(1.3, 0.2, 2.1, 6),
        area_oracles::HyperboloidSurface<double>(1, 0.5, -1, -0.3, 1.2, 2,
                                                 5.5)};
    for (const Surface &s : surfaces)
        for (double u : {0.1, 0.45, 0.9})
            for (double v : {0.1, 0.5, 0.9}) {
                auto p = s(u, v);
                auto u0 = s(u - h, v), u1 = s(u + h, v);
                auto v0 = s(u, v - h), v1 = s(u, v + h);
                for (int k = 0; k < 3; ++k) {
                    EXPECT_NEAR(p.dpdu[k], (u1.p[k] - u0.p[k]) / (2 * h),
                                1e-5);
                    EXPECT_NEAR(p.dpdv[k], (v1.p[k] - v0.p[k]) / (2 * h),
                                1e-5);
                }
            }
}

TEST(QuadricAreaQuadrature, Cylinders) {
    QuadricSampler sampler(calls::Seed(0x5eed0404));
    for (int i = 0; i < kQuadricCases; ++i) {
        CylinderParams c = sampler.Cylinder();
        ExpectMatches(Area(c),
                      {CylinderByParametrization(c), CylinderByProfile(c)},
                      Describe(c));
    }
}

TEST(QuadricAreaQuadrature, Cones) {
    QuadricSampler sampler(calls::Seed(0x5eed0405));
    for (int i = 0; i < kQuadricCases; ++i) {
        ConeParams c = sampler.Cone();
        ExpectMatches(Area(c), {ConeByParametrization(c), ConeByProfile(c)},
                      Describe(c));
    }
}

EXERCISE_TEST(Ex4_12_ParaboloidQuadrature, MatchesThreeIntegrals) {
    QuadricSampler sampler(calls::Seed(0x5eed0406));
    for (int i = 0; i < kQuadricCases; ++i) {
        ParaboloidParams p = sampler.Paraboloid();
        Float area = ex::ParaboloidArea(Transform(), false, p.radius, p.z0,
                                        p.z1, p.phiMaxDegrees);
        ExpectMatches(area,
                      {ParaboloidByParametrization(p), ParaboloidByGraph(p),
                       ParaboloidByRadius(p)},
                      Describe(p));
    }
}

TEST(QuadricAreaQuadrature, Hyperboloids) {
    QuadricSampler sampler(calls::Seed(0x5eed0407));
    for (int i = 0; i < kQuadricCases; ++i) {
        HyperboloidParams h = sampler.Hyperboloid(i % 5);
        ExpectMatches(Area(h),
                      {HyperboloidByParametrization(h),
                       HyperboloidByProfile(h)},
                      Describe(h));
    }
}

// A vertical segment sweeps a cylinder, a segment ending on the axis a cone:
// the hyperboloid's area must be theirs, to rounding, and both must match the
// integrals.
TEST(QuadricAreaQuadrature, HyperboloidAsCylinderAndCone) {
    QuadricSampler sampler(calls::Seed(0x5eed0408));
    for (int i = 0; i < kQuadricCases / 4; ++i) {
        CylinderParams c = sampler.Cylinder();
        Float hyperboloid =
            Area(HyperboloidParams{Point3f(c.radius, 0, c.z0),
                                   Point3f(c.radius, 0, c.z1),
                                   c.phiMaxDegrees});
        // The same cylinder, with its radius along another direction.
        Float turned = Area(HyperboloidParams{
            Point3f(Float(0.6) * c.radius, Float(0.8) * c.radius, c.z0),
            Point3f(Float(0.6) * c.radius, Float(0.8) * c.radius, c.z1),
            c.phiMaxDegrees});
        ExpectMatches(hyperboloid, {CylinderByParametrization(c)},
                      Describe(c));
        ExpectMatches(turned, {CylinderByParametrization(c)}, Describe(c));
        EXPECT_LE(RelativeDifference(hyperboloid, Area(c)), kAreaRelTol)
            << Describe(c);

        ConeParams k = sampler.Cone();
        Float asCone = Area(HyperboloidParams{Point3f(k.radius, 0, 0),
                                              Point3f(0, 0, k.height),
                                              k.phiMaxDegrees});
        Float upsideDown = Area(HyperboloidParams{
            Point3f(0, 0, k.height), Point3f(0, k.radius, 0),
            k.phiMaxDegrees});
        ExpectMatches(asCone, {ConeByParametrization(k)}, Describe(k));
        ExpectMatches(upsideDown, {ConeByParametrization(k)}, Describe(k));
        EXPECT_LE(RelativeDifference(asCone, Area(k)), kAreaRelTol)
            << Describe(k);
    }
}

// Plausible wrong formulas must fail against the same oracles.
TEST(AreaQuadrature, RejectsWrongQuadricFormulas) {
    // A cone of height 2 and radius 1.5: without the slant, or the whole
    // disk of its base.
    ConeParams cone{2, 1.5, 360};
    double coneArea = ConeByParametrization(cone).value;
    double l = std::sqrt(2.0 * 2 + 1.5 * 1.5);
    EXPECT_LE(RelativeDifference(kPi * 1.5 * l, coneArea), kTotalRelTol);
    for (double wrong : {kPi * 1.5 * 2, 2 * kPi * 1.5 * l, kPi * 1.5 * 1.5})
        EXPECT_GT(RelativeDifference(wrong, coneArea), kTotalRelTol) << wrong;

    // A paraboloid with its tip: without the slope factor (phiMax int f dz),
    // or its rim's disk.
    ParaboloidParams dish{1.5, 0, 2, 360};
    double dishArea = ParaboloidByParametrization(dish).value;
    double flat = 2 * kPi * 1.5 * (2.0 / 3.0) * 2;  // 2 pi r (2/3) zMax
    EXPECT_GT(RelativeDifference(flat, dishArea), kTotalRelTol);
    EXPECT_GT(RelativeDifference(kPi * 1.5 * 1.5, dishArea), kTotalRelTol);

    // A skew segment: the distance from the axis integrated along the
    // segment's length overcounts; so does the cone of the asymptotes.
    HyperboloidParams skew{Point3f(1, 0, -1), Point3f(0, 1, 1), 360};
    double skewArea = HyperboloidByParametrization(skew).value;
    EXPECT_LE(RelativeDifference(skewArea, HyperboloidByProfile(skew).value),
              kTotalRelTol);
    double dLength = std::sqrt(1 + 1 + 4.0);
    Integral alongSegment = Integrate(
        [](double v) { return std::hypot(1 - v, v); }, 0, 1);
    EXPECT_GT(RelativeDifference(2 * kPi * dLength * alongSegment.value,
                                 skewArea),
              kTotalRelTol);
}
