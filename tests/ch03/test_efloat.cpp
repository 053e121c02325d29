// Tests of EFloat (running error bounds) and of the EFloat Quadratic().
// The oracle is long double arithmetic (64-bit mantissa on x86-64), which is
// exact for the products of two floats and much more precise than double.
#include "lrt/core/efloat.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

using namespace lrt;

namespace {

typedef long double LD;

// Number of random expression trees and perturbations of their leaves.
constexpr int kTrees = 20000;
constexpr int kPerturbations = 4;
// Number of random interval quadratics and of exact quadratics.
constexpr int kQuadratics = 100000;

bool Contains(const EFloat &e, LD x) {
    return (LD)e.LowerBound() <= x && x <= (LD)e.UpperBound();
}

// A random expression tree. Leaves are EFloats with a value and an error
// bound; inner nodes apply one operation to one or two children.
enum Op { Leaf, Add, Sub, Mul, Div, SqrtAbs, AbsOp, Neg };

struct Node {
    Op op;
    int a = -1, b = -1;
    Float v = 0, err = 0;
};

struct Tree {
    std::vector<Node> nodes;
    int root = -1;
};

Float RandomLeafValue(std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> u(0, 1);
    double kind = u(rng);
    if (kind < 0.05) return 0;
    if (kind < 0.15) return Float(int(u(rng) * 21) - 10);
    double mag = std::pow(10.0, -3 + 6 * u(rng));
    return Float(u(rng) < 0.5 ? -mag : mag);
}

Float RandomLeafError(std::mt19937_64 &rng, Float v) {
    std::uniform_real_distribution<double> u(0, 1);
    double kind = u(rng);
    if (kind < 0.4) return 0;
    if (kind < 0.8) return Float(std::abs(v) * std::pow(10.0, -8 + 5 * u(rng)));
    return Float(std::pow(10.0, -6 + 6 * u(rng)));
}

int Grow(Tree &t, std::mt19937_64 &rng, int depth) {
    std::uniform_real_distribution<double> u(0, 1);
    Node n;
    if (depth == 0 || u(rng) < 0.25) {
        n.op = Leaf;
        n.v = RandomLeafValue(rng);
        n.err = RandomLeafError(rng, n.v);
    } else {
        n.op = Op(1 + int(u(rng) * 7) % 7);
        n.a = Grow(t, rng, depth - 1);
        if (n.op == Add || n.op == Sub || n.op == Mul || n.op == Div)
            n.b = Grow(t, rng, depth - 1);
    }
    t.nodes.push_back(n);
    return int(t.nodes.size()) - 1;
}

EFloat EvalE(const Tree &t, int i, std::vector<EFloat> &out) {
    const Node &n = t.nodes[i];
    EFloat r;
    switch (n.op) {
    case Leaf: r = EFloat(n.v, n.err); break;
    case Add: r = EvalE(t, n.a, out) + EvalE(t, n.b, out); break;
    case Sub: r = EvalE(t, n.a, out) - EvalE(t, n.b, out); break;
    case Mul: r = EvalE(t, n.a, out) * EvalE(t, n.b, out); break;
    case Div: r = EvalE(t, n.a, out) / EvalE(t, n.b, out); break;
    case SqrtAbs: r = sqrt(abs(EvalE(t, n.a, out))); break;
    case AbsOp: r = abs(EvalE(t, n.a, out)); break;
    case Neg: r = -EvalE(t, n.a, out); break;
    }
    out[i] = r;
    return r;
}

// Evaluates the tree in long double, with every leaf moved to a point of its
// interval: leafPos[i] in [-1, 1] scales the leaf's error bound.
LD EvalLD(const Tree &t, int i, const std::vector<double> &leafPos,
          std::vector<LD> &out) {
    const Node &n = t.nodes[i];
    LD r = 0;
    switch (n.op) {
    case Leaf: r = (LD)n.v + (LD)leafPos[i] * (LD)n.err; break;
    case Add: r = EvalLD(t, n.a, leafPos, out) + EvalLD(t, n.b, leafPos, out);
        break;
    case Sub: r = EvalLD(t, n.a, leafPos, out) - EvalLD(t, n.b, leafPos, out);
        break;
    case Mul: r = EvalLD(t, n.a, leafPos, out) * EvalLD(t, n.b, leafPos, out);
        break;
    case Div: r = EvalLD(t, n.a, leafPos, out) / EvalLD(t, n.b, leafPos, out);
        break;
    case SqrtAbs: r = std::sqrt(std::abs(EvalLD(t, n.a, leafPos, out))); break;
    case AbsOp: r = std::abs(EvalLD(t, n.a, leafPos, out)); break;
    case Neg: r = -EvalLD(t, n.a, leafPos, out); break;
    }
    out[i] = r;
    return r;
}

}  // namespace

TEST(EFloat, ConstructorEnclosesValueAndError) {
    std::mt19937_64 rng(301);
    for (int i = 0; i < 100000; ++i) {
        Float v = RandomLeafValue(rng), err = RandomLeafError(rng, v);
        EFloat e(v, err);
        EXPECT_EQ((Float)e, v);
        ASSERT_LE((LD)e.LowerBound(), (LD)v - (LD)err);
        ASSERT_GE((LD)e.UpperBound(), (LD)v + (LD)err);
        if (err == 0) {
            EXPECT_EQ(e.LowerBound(), v);
            EXPECT_EQ(e.UpperBound(), v);
        }
    }
    // A negative error bound is read as its magnitude.
    EFloat neg(1, -0.5f);
    EXPECT_LE(neg.LowerBound(), 0.5f);
    EXPECT_GE(neg.UpperBound(), 1.5f);
}

TEST(EFloat, BoundsContainLongDoubleOverRandomExpressionTrees) {
    std::mt19937_64 rng(302);
    std::uniform_real_distribution<double> u(-1, 1);
    long checked = 0, skipped = 0, infinite = 0;
    for (int ti = 0; ti < kTrees; ++ti) {
        Tree t;
        t.root = Grow(t, rng, 1 + ti % 6);
        std::vector<EFloat> e(t.nodes.size());
        EvalE(t, t.root, e);
        for (int k = 0; k < kPerturbations; ++k) {
            std::vector<double> pos(t.nodes.size());
            for (double &p : pos)
                p = (k == 0) ? 0 : (k == 1) ? (u(rng) < 0 ? -1 : 1) : u(rng);
            std::vector<LD> x(t.nodes.size());
            EvalLD(t, t.root, pos, x);
            for (size_t i = 0; i < t.nodes.size(); ++i) {
                ASSERT_FALSE(std::isnan(e[i].LowerBound()) ||
                             std::isnan(e[i].UpperBound()))
                    << "tree " << ti << " node " << i;
                ASSERT_LE(e[i].LowerBound(), e[i].UpperBound());
                if (!std::isfinite(x[i])) {
                    ++skipped;
                    continue;
                }
                if (std::isinf(e[i].LowerBound()) ||
                    std::isinf(e[i].UpperBound()))
                    ++infinite;
                ASSERT_TRUE(Contains(e[i], x[i]))
                    << "tree " << ti << " node " << i << " op "
                    << t.nodes[i].op << ": " << (double)x[i] << " not in ["
                    << e[i].LowerBound() << ", " << e[i].UpperBound() << "]";
                ++checked;
                // The plain floating-point value is inside its own interval.
                Float v = (Float)e[i];
                if (std::isfinite(v)) {
                    ASSERT_LE(e[i].LowerBound(), v);
                    ASSERT_GE(e[i].UpperBound(), v);
                }
            }
        }
    }
    std::printf("[ EFloat   ] %ld node values checked, %ld non-finite "
                "long double values skipped, %ld infinite intervals\n",
                checked, skipped, infinite);
    EXPECT_GT(checked, 250000);
    EXPECT_LT(skipped, checked / 20);
}

TEST(EFloat, PreciseValue) {
    EFloat a(Float(0.1)), b(Float(0.2));
    EFloat s = a + b;
#ifdef LRT_EFLOAT_PRECISE
    EXPECT_EQ(s.PreciseValue(), (LD)Float(0.1) + (LD)Float(0.2));
#else
    EXPECT_EQ(s.PreciseValue(), (LD)(Float)s);
#endif
    EXPECT_TRUE(Contains(s, (LD)Float(0.1) + (LD)Float(0.2)));
    EXPECT_GT(s.GetAbsoluteError(), 0);
    EXPECT_LE(s.GetAbsoluteError(), 4 * MachineEpsilon);
}

TEST(EFloat, DivisionByIntervalContainingZeroIsUnbounded) {
    EFloat one(1), z(0, Float(1e-3)), exactZero(0), touching(0.5f, 0.5f);
    for (EFloat d : {z, exactZero, touching}) {
        EFloat q = one / d;
        EXPECT_EQ(q.LowerBound(), -Infinity);
        EXPECT_EQ(q.UpperBound(), Infinity);
    }
    EFloat q = one / EFloat(4, 1);
    EXPECT_LE(q.LowerBound(), Float(1) / 5);
    EXPECT_GE(q.UpperBound(), Float(1) / 3);
}

TEST(EFloat, InfiniteBoundsNeverTurnIntoNaN) {
    EFloat all = EFloat(1) / EFloat(0, 1);  // the whole real line
    EFloat zero(0);
    for (EFloat r : {all * zero, zero * all, all * all, all + all, all - all,
                     all / EFloat(2, 1), sqrt(abs(all)), -all, abs(all)}) {
        EXPECT_FALSE(std::isnan(r.LowerBound()));
        EXPECT_FALSE(std::isnan(r.UpperBound()));
        EXPECT_LE(r.LowerBound(), 0);
        EXPECT_GE(r.UpperBound(), 0);
    }
}

TEST(EFloat, SqrtAndAbsEdgeCases) {
    // An interval that extends below zero: the square root starts at zero.
    EFloat s = sqrt(EFloat(Float(1e-8), Float(1e-6)));
    EXPECT_EQ(s.LowerBound(), 0);
    EXPECT_GE(s.UpperBound(), std::sqrt(Float(1.01e-6)));
    EFloat s4 = sqrt(EFloat(4));
    EXPECT_EQ((Float)s4, 2);
    EXPECT_LT(s4.LowerBound(), 2);
    EXPECT_GT(s4.UpperBound(), 2);
    EFloat a = abs(EFloat(-1, 2));  // [-3, 1] becomes [0, 3]
    EXPECT_EQ(a.LowerBound(), 0);
    EXPECT_GE(a.UpperBound(), 3);
    EXPECT_EQ((Float)a, 1);
    EFloat b = abs(EFloat(-5, 1));
    EXPECT_EQ((Float)b, 5);
    EXPECT_GE(b.LowerBound(), 3.9f);
    EXPECT_LE(b.LowerBound(), 4);
}

namespace {

// Roots of a x^2 + b x + c in long double; false if complex.
bool LDRoots(LD a, LD b, LD c, LD *r0, LD *r1) {
    LD disc = b * b - 4 * a * c;
    if (disc < 0) return false;
    LD root = std::sqrt(disc);
    LD q = (b < 0) ? -0.5L * (b - root) : -0.5L * (b + root);
    *r0 = q / a;
    *r1 = (q != 0) ? c / q : *r0;
    if (*r0 > *r1) std::swap(*r0, *r1);
    return true;
}

LD RelErr(LD x, LD ref) {
    return ref == 0 ? std::abs(x) : std::abs((x - ref) / ref);
}

}  // namespace

TEST(EFloatQuadratic, IntervalsContainRootsOfAllCoefficientsInBounds) {
    std::mt19937_64 rng(303);
    std::uniform_real_distribution<double> u(-1, 1);
    long contained = 0, trueCount = 0, falseCount = 0;
    for (int i = 0; i < kQuadratics; ++i) {
        // Build coefficients from random roots, so that many have real
        // roots, including close pairs.
        double r0 = std::pow(10.0, 3 * u(rng)) * (u(rng) < 0 ? -1 : 1);
        double r1 = (i % 4 == 0) ? r0 * (1 + std::pow(10.0, -7 + 3 * u(rng)))
                                 : std::pow(10.0, 3 * u(rng)) * u(rng);
        double sa = std::pow(10.0, 2 * u(rng));
        Float av = Float(sa), bv = Float(-sa * (r0 + r1)),
              cv = Float(sa * r0 * r1);
        if (i % 10 == 0) cv = Float(cv + std::abs(cv) * 0.5 * u(rng));
        Float ae = (i % 3 == 0) ? 0 : Float(std::abs(av) * 1e-6 * (u(rng) + 1));
        Float be = (i % 3 == 0) ? 0 : Float(std::abs(bv) * 1e-6 * (u(rng) + 1));
        Float ce = (i % 3 == 0) ? 0 : Float(std::abs(cv) * 1e-6 * (u(rng) + 1));
        EFloat a(av, ae), b(bv, be), c(cv, ce), t0, t1;
        bool found = Quadratic(a, b, c, &t0, &t1);
        // The decision is made on the discriminant of the values, which
        // DifferenceOfProducts computes with a small relative error.
        LD discV = (LD)bv * bv - 4 * (LD)av * cv;
        LD slack = std::ldexp((LD)1, -60) * ((LD)bv * bv + 4 * std::abs((LD)av * cv));
        if (found) {
            ++trueCount;
            ASSERT_GE(discV, -slack) << i;
            ASSERT_LE((Float)t0, (Float)t1);
        } else {
            ++falseCount;
            ASSERT_LE(discV, slack) << i;
            continue;
        }
        for (int k = 0; k < 4; ++k) {
            LD pa = (LD)av + (k == 0 ? 0 : u(rng)) * ae;
            LD pb = (LD)bv + (k == 0 ? 0 : u(rng)) * be;
            LD pc = (LD)cv + (k == 0 ? 0 : u(rng)) * ce;
            LD x0, x1;
            if (!LDRoots(pa, pb, pc, &x0, &x1)) continue;
            bool disjoint = t0.UpperBound() < t1.LowerBound();
            if (disjoint) {
                ASSERT_TRUE(Contains(t0, x0)) << i << " root " << (double)x0;
                ASSERT_TRUE(Contains(t1, x1)) << i << " root " << (double)x1;
            } else {
                ASSERT_TRUE(Contains(t0, x0) || Contains(t1, x0)) << i;
                ASSERT_TRUE(Contains(t0, x1) || Contains(t1, x1)) << i;
            }
            ++contained;
        }
    }
    std::printf("[ EFloat   ] %ld quadratics with roots, %ld without, %ld "
                "perturbed root pairs contained\n", trueCount, falseCount,
                contained);
    EXPECT_GT(contained, 2 * kQuadratics);
}

TEST(EFloatQuadratic, ValuesAreAccurateForExactCoefficients) {
    std::mt19937_64 rng(304);
    std::uniform_real_distribution<double> u(-1, 1);
    LD worst = 0;
    int tested = 0;
    for (int i = 0; i < kQuadratics; ++i) {
        double r0 = std::pow(10.0, 4 * u(rng)) * (u(rng) < 0 ? -1 : 1);
        double r1 = std::pow(10.0, 4 * u(rng)) * (u(rng) < 0 ? -1 : 1);
        if (std::abs(r0 - r1) < 1e-2 * std::max(std::abs(r0), std::abs(r1)))
            continue;
        double sa = std::pow(10.0, 2 * u(rng));
        Float av = Float(sa), bv = Float(-sa * (r0 + r1)),
              cv = Float(sa * r0 * r1);
        LD x0, x1;
        if (!LDRoots(av, bv, cv, &x0, &x1)) continue;
        EFloat t0, t1;
        ASSERT_TRUE(Quadratic(EFloat(av), EFloat(bv), EFloat(cv), &t0, &t1));
        worst = std::max(worst, RelErr((Float)t0, x0));
        worst = std::max(worst, RelErr((Float)t1, x1));
        ASSERT_TRUE(Contains(t0, x0));
        ASSERT_TRUE(Contains(t1, x1));
        ++tested;
    }
    std::printf("[ EFloat   ] %d exact quadratics: largest relative error of "
                "a root value %.3g machine epsilons\n", tested,
                (double)(worst / MachineEpsilon));
    EXPECT_LE(worst, 8 * (LD)MachineEpsilon);
}

TEST(EFloatQuadratic, StableFormAvoidsTextbookCancellation) {
    // x^2 + b x + 1 with b = 4 / sqrt(eps): the small root is about -1/b.
    // The textbook formula computes it as (-b + sqrt(b^2 - 4)) / 2, and
    // b^2 - 4 rounds to b^2, so the difference cancels completely.
    Float b = 4 / std::sqrt(MachineEpsilon);
    LD x0, x1;
    ASSERT_TRUE(LDRoots(1, b, 1, &x0, &x1));
    Float textbook = (-b + std::sqrt(b * b - 4)) / 2;
    EFloat t0, t1;
    ASSERT_TRUE(Quadratic(EFloat(1), EFloat(b), EFloat(1), &t0, &t1));
    EXPECT_GT(RelErr(textbook, x1), 0.1);
    EXPECT_LE(RelErr((Float)t1, x1), 4 * (LD)MachineEpsilon);
    EXPECT_LE(RelErr((Float)t0, x0), 4 * (LD)MachineEpsilon);
}

TEST(EFloatQuadratic, DegenerateAndInvalidCoefficients) {
    EFloat t0(7), t1(7);
    // a = b = 0: no root to report; outputs untouched.
    EXPECT_FALSE(Quadratic(EFloat(0), EFloat(0), EFloat(1), &t0, &t1));
    EXPECT_EQ((Float)t0, 7);
    // a = 0: the linear root, twice.
    ASSERT_TRUE(Quadratic(EFloat(0), EFloat(2), EFloat(-3), &t0, &t1));
    EXPECT_EQ((Float)t0, 1.5f);
    EXPECT_EQ((Float)t1, 1.5f);
    // Complex roots.
    EXPECT_FALSE(Quadratic(EFloat(1), EFloat(0), EFloat(1), &t0, &t1));
    // A double root, and the double root at zero (q = 0).
    ASSERT_TRUE(Quadratic(EFloat(1), EFloat(-4), EFloat(4), &t0, &t1));
    EXPECT_EQ((Float)t0, 2);
    EXPECT_EQ((Float)t1, 2);
    ASSERT_TRUE(Quadratic(EFloat(1), EFloat(0), EFloat(0), &t0, &t1));
    EXPECT_EQ((Float)t0, 0);
    EXPECT_EQ((Float)t1, 0);
    // NaN anywhere: no roots.
    Float nan = std::numeric_limits<Float>::quiet_NaN();
    EXPECT_FALSE(Quadratic(EFloat(nan), EFloat(1), EFloat(1), &t0, &t1));
    EXPECT_FALSE(Quadratic(EFloat(1), EFloat(nan), EFloat(1), &t0, &t1));
    EXPECT_FALSE(Quadratic(EFloat(1), EFloat(1), EFloat(nan), &t0, &t1));
    EXPECT_FALSE(Quadratic(EFloat(0), EFloat(1), EFloat(nan), &t0, &t1));
    Float inf = Infinity;
    EXPECT_FALSE(Quadratic(EFloat(1), EFloat(inf), EFloat(inf), &t0, &t1));
}
