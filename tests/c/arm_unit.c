/* SPDX-License-Identifier: BSD-2-Clause */
/* The arm body's gap (arm_body.c) against the tip's height and rates written here
 * independently: the rows the error control uses are the derivatives of y and w, the gap
 * measured from a reference is the tip's height, exact to its own size near the reference,
 * and y_resolution bounds the move of y by one ulp of an angle. Random arms and states from a
 * fixed seed. Built by tests/c/CMakeLists.txt, run by tests/fmu/test_c_robustness.py; exit
 * status 0 only if every check passed. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "arm_body.h"
#include "unit_check.h"

static uint64_t seed = 20261127;

static double uniform(double lo, double hi)
{
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (double)(seed >> 11) / 9007199254740992.0;
}

static bool close_to(double a, double b, double tol)
{
    return fabs(a - b) <= tol;
}

int main(void)
{
    for (int n = 0; n < 200; ++n) {
        const double l1 = uniform(0.1, 0.9);
        ArmBody b = { .m1 = uniform(0.1, 0.9), .l1 = l1, .J1 = uniform(0, 0.1), .l2 = 1 - l1,
                      .J2 = uniform(0, 0.1), .H = uniform(0, 1) };
        b.m2 = 1 - b.m1;
        const double x[ARM_NX] = { uniform(-M_PI, 0), uniform(-M_PI, 0), uniform(-3, 3), uniform(-3, 3) };
        const double t1 = x[ARM_THETA1], t2 = x[ARM_THETA2], w1 = x[ARM_OMEGA1], w2 = x[ARM_OMEGA2];
        const double y_here = b.H + b.l1 * sin(t1) + b.l2 * sin(t2);
        const double w_here = b.l1 * cos(t1) * w1 + b.l2 * cos(t2) * w2;
        const double scale = 1e-14 * (b.H + 1);

        /* from angles 0 and from a random reference, y is the tip's height */
        const double r1 = uniform(-M_PI, 0), r2 = uniform(-M_PI, 0);
        for (int with_ref = 0; with_ref < 2; ++with_ref) {
            arm_set_reference(&b, with_ref ? r1 : 0, with_ref ? r2 : 0, false);
            const Contact c = { .body = &arm_body, .params = &b, .law = { .epsilon = 1e-4, .delta = 1, .mu = 1 } };
            const BodyState s = contact_body(&c, x);
            CHECK(close_to(s.y, y_here, scale), "y %.17g, the tip's height %.17g", s.y, y_here);
            CHECK(close_to(s.w, w_here, scale * 3), "w %.17g, the tip's rate %.17g", s.w, w_here);

            ContactGapRows g;
            CHECK(contact_gap_rows(&c, x, &g), "the arm gives rows");
            const double dy[ARM_NX] = { l1 * cos(t1), b.l2 * cos(t2), 0, 0 };
            const double dw[ARM_NX] = { -l1 * sin(t1) * w1, -b.l2 * sin(t2) * w2, l1 * cos(t1), b.l2 * cos(t2) };
            for (int i = 0; i < ARM_NX; ++i) {
                CHECK(close_to(g.y[i], dy[i], 1e-15), "dy/dx[%d] %.17g, analytic %.17g", i, g.y[i], dy[i]);
                CHECK(close_to(g.w[i], dw[i], 1e-14), "dw/dx[%d] %.17g, analytic %.17g", i, g.w[i], dw[i]);
            }
            CHECK(g.y_value == s.y && g.w_value == s.w, "the rows' values are the body's y, w");
            CHECK(g.y_scale == 1e-8 && g.w_scale == 1e-4, "the rows' scales are eps^2, eps");

            /* one ulp of either angle moves y by at most y_resolution */
            for (int i = 0; i < 2; ++i) {
                double x1[ARM_NX] = { t1, t2, w1, w2 };
                x1[i] = nextafter(x1[i], INFINITY);
                const BodyState s1 = contact_body(&c, x1);
                CHECK(fabs(s1.y - s.y) <= s.y_resolution + s.y_noise + s1.y_noise,
                      "an ulp of theta%d moves y by %.3g > resolution %.3g", i + 1, fabs(s1.y - s.y), s.y_resolution);
            }
        }

        /* on the floor at the reference: y = 0 exactly there, and its rise by a small turn of the
         * angles is l cos(r) d - l sin(r) d^2/2 to O(d^3), as the absolute form could not give */
        arm_set_reference(&b, t1, t2, true);
        const Contact c = { .body = &arm_body, .params = &b, .law = { .epsilon = 1e-4, .delta = 1, .mu = 1 } };
        CHECK(contact_body(&c, x).y == 0, "y at the reference on the floor is %.3g", contact_body(&c, x).y);
        const double d1 = uniform(-1e-9, 1e-9), d2 = uniform(-1e-9, 1e-9);
        const double xd[ARM_NX] = { t1 + d1, t2 + d2, w1, w2 };
        const double e1 = xd[0] - t1, e2 = xd[1] - t2;   /* the turns as stored */
        const double rise = l1 * (cos(t1) * e1 - 0.5 * sin(t1) * e1 * e1) + b.l2 * (cos(t2) * e2 - 0.5 * sin(t2) * e2 * e2);
        const double y = contact_body(&c, xd).y;
        CHECK(close_to(y, rise, 1e-12 * fabs(rise) + 1e-27), "y %.17g near the reference, its rise %.17g", y, rise);
    }
    printf("arm_unit: %d checks, %d failed\n%s\n", checks, failures, failures ? "" : "all checks passed");
    return failures != 0;
}
