// Hidden tests of exercise ex-3.25 (the quadric's quadratic) for the four
// quadrics, against the long-double oracle of ch03/quadrics_oracle.h: cases
// the public suites Ex3_25_Cylinder, Ex3_25_Cone, Ex3_25_Paraboloid and
// Ex3_25_Hyperboloid do not show (other cuts and sizes, other distances,
// rays along the lines of cones whose height is not their radius, and
// degenerate hyperboloids of other shapes under other transformations).
// They reach the shapes only through the exercise call IntersectQuadric(),
// draw their cases from calls::Seed() and state their counts with
// calls::Cases(). (A file of its own: the oracle's helpers share names with
// those of test_ex3_hidden.cpp.)
#include "ch03/quadrics_oracle.h"

#include <cmath>
#include <vector>

// Thin slices, narrow wedges and swapped ends, and one of each shape small
// and one large.
EXERCISE_TEST(Ex3_25_QuadricsHidden, OtherCutsAndSizes) {
    RunOracle("Cylinder (hidden)",
              {CylinderDef(0.4, 2, -0.5, 35, "narrow cylinder, z swapped"),
               CylinderDef(30, -0.1, 0.1, 300, "wide thin cylinder")},
              lrt::calls::Seed(3600));
    RunOracle("Cone (hidden)",
              {ConeDef(5, 0.2, 40, "thin cone wedge"),
               ConeDef(0.01, 0.03, 359, "tiny cone")},
              lrt::calls::Seed(3601));
    RunOracle("Paraboloid (hidden)",
              {ParaboloidDef(3, 1.9, 2, 180, "paraboloid rim"),
               ParaboloidDef(0.2, 5, 0, 45, "deep narrow paraboloid wedge")},
              lrt::calls::Seed(3602));
    RunOracle("Hyperboloid (hidden)",
              {HyperboloidDef(D3(-1, 0.2, 0.5), D3(1, 0.3, -0.5), 90,
                              "hyperboloid, segment crossing near the axis"),
               HyperboloidDef(D3(2, 2, 0), D3(2.5, 1, 0.1), 330,
                              "flat hyperboloid ring")},
              lrt::calls::Seed(3603));
}

// Shapes 1e3 and 3e4 from the world's origin, rays from near the world's
// origin and from 5e3 away.
EXERCISE_TEST(Ex3_25_QuadricsHidden, OtherDistances) {
    RunFar("Cylinder (hidden)", {CylinderDef(0.5, -2, 1, 200, "cylinder")},
           lrt::calls::Seed(3610), 1e3, 5e3);
    RunFar("Cone (hidden)", {ConeDef(0.7, 1.2, 300, "cone")},
           lrt::calls::Seed(3611), 3e4, 5e3);
    RunFar("Paraboloid (hidden)",
           {ParaboloidDef(1, 0.2, 1.5, 250, "paraboloid")},
           lrt::calls::Seed(3612), 3e4, 5e3);
    RunFar("Hyperboloid (hidden)",
           {HyperboloidDef(D3(0.3, -1, -1), D3(1, 0.5, 0.5), 360,
                           "hyperboloid")},
           lrt::calls::Seed(3613), 1e3, 5e3);
}

// Rays along the lines of cones of several slopes (the quadratic's leading
// coefficient vanishes up to rounding), turned and scaled; and degenerate
// hyperboloids of other sizes, a segment parallel to the axis and one
// through it, also under a mirroring nonuniform scale, against Cylinder
// and Cone.
EXERCISE_TEST(Ex3_25_QuadricsHidden, ConeLinesAndDegenerateHyperboloids) {
    Rng rng(lrt::calls::Seed(3620));
    const int rays = lrt::calls::Cases(2000, 100);
    for (double slope : {0.3, 2.5}) {
        QuadricDef def = ConeDef(slope, 1, 320, "cone");
        Geom g(def);
        Affine A = Affine::Make(D3(1.5, -0.8, 1.1), D3(1, 2, -1), 63,
                                D3(2, -1, 3));
        lrt::Transform o2w = A.ToTransform();
        LAffine M(o2w);
        QTarget cone = Target(def, o2w, false);
        QStats st;
        for (int i = 0; i < rays; ++i) {
            // Parallel to the line from the base circle at phi to the apex,
            // through a point of the cone, which is then its only root.
            double phi = rng.U(0, 2 * kPi);
            L3 d(-std::cos(phi), -std::sin(phi), (LD)g.h);
            L3 q = g.P(rng.U(0.02, 0.98), rng.U(0.02, 0.98));
            L3 o = q - (LD)rng.U(0.2, 3) * d;
            lrt::Ray wr(ToP(M.Point(o)), ToV((LD)rng.U(0.5, 2) * M.Vector(d)));
            CheckRay(cone, g, M, false, wr, "cone line", true, st);
        }
        QReport("Cone (hidden) along its lines", st);
        EXPECT_EQ(st.failures, 0);
        EXPECT_GT(st.hits, rays / 2);
    }
    CompareWithEquivalent(
        HyperboloidDef(D3(2, 0, -1), D3(2, 0, 0.5), 150, "wide hyperboloid"),
        CylinderDef(2, -1, 0.5, 150, "cylinder"), lrt::calls::Seed(3621));
    CompareWithEquivalent(
        HyperboloidDef(D3(0.75, 0, 0), D3(0, 0, 3), 240, "tall hyperboloid"),
        ConeDef(3, 0.75, 240, "cone"), lrt::calls::Seed(3622));
}
