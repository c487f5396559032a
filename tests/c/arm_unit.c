/* SPDX-License-Identifier: BSD-2-Clause */
/* The arm body's gap (arm_body.c) against the tip's height and rates written here
 * independently: y's start is the tip's height (0 exactly for a tip placed on the floor), the
 * gap state is the body's y and integrates by w, and the rows the error control uses are the
 * derivatives of y and w. Random arms and states from a
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
        const double t1 = uniform(-M_PI, 0), t2 = uniform(-M_PI, 0), w1 = uniform(-3, 3), w2 = uniform(-3, 3);
        const double y_here = b.H + b.l1 * sin(t1) + b.l2 * sin(t2);
        const double w_here = b.l1 * cos(t1) * w1 + b.l2 * cos(t2) * w2;
        const double scale = 1e-14 * (b.H + 1);
        const Contact c = { .body = &arm_body, .params = &b, .law = { .epsilon = 1e-4, .delta = 1, .mu = 1 } };

        /* the start of y is the tip's height; the state y is the body's gap, exactly */
        CHECK(close_to(arm_height(&b, t1, t2), y_here, scale), "arm_height %.17g, the tip's height %.17g",
              arm_height(&b, t1, t2), y_here);
        const double y_state = uniform(-1e-3, 1e-3);
        const double x[ARM_NX] = { t1, t2, w1, w2, y_state };
        const BodyState s = contact_body(&c, x);
        CHECK(s.y == y_state && s.y_noise == 0, "y is the state: %.17g", s.y);
        CHECK(close_to(s.w, w_here, scale * 3), "w %.17g, the tip's rate %.17g", s.w, w_here);

        /* y' = w: the core integrates the gap state by the tip's normal rate */
        double dx[ARM_NX];
        contact_derivatives(&c, (ContactMode){ .contact = false, .slip = 1 }, x, dx);
        CHECK(dx[ARM_Y] == s.w && dx[ARM_THETA1] == w1 && dx[ARM_THETA2] == w2, "y' %.17g, w %.17g", dx[ARM_Y], s.w);
        CHECK(contact_nx(&arm_body) == ARM_NX, "the core counts %d states", contact_nx(&arm_body));

        /* the rows: y moves with its state alone, w with the angles and rates */
        ContactGapRows g;
        CHECK(contact_gap_rows(&c, x, &g), "the arm gives rows");
        const double dy[ARM_NX] = { 0, 0, 0, 0, 1 };
        const double dw[ARM_NX] = { -l1 * sin(t1) * w1, -b.l2 * sin(t2) * w2, l1 * cos(t1), b.l2 * cos(t2), 0 };
        for (int i = 0; i < ARM_NX; ++i) {
            CHECK(g.y[i] == dy[i], "dy/dx[%d] %.17g, analytic %.17g", i, g.y[i], dy[i]);
            CHECK(close_to(g.w[i], dw[i], 1e-14), "dw/dx[%d] %.17g, analytic %.17g", i, g.w[i], dw[i]);
        }
        CHECK(g.y_value == s.y && g.w_value == s.w, "the rows' values are the body's y, w");
        CHECK(g.y_scale == 1e-8 && g.w_scale == 1e-4, "the rows' scales are eps^2, eps");

        /* a tip placed on the floor starts exactly on it; one an ulp-sized fraction of L above
         * does not (the rounding of the sum decides, not the placement) */
        ArmBody on = b;
        on.H = -(l1 * sin(t1) + b.l2 * sin(t2));
        CHECK(arm_height(&on, t1, t2) == 0, "a tip placed on the floor is at %.3g", arm_height(&on, t1, t2));
        on.H += 1e-9;
        CHECK(close_to(arm_height(&on, t1, t2), 1e-9, 1e-14), "a tip 1e-9 above it is at %.17g", arm_height(&on, t1, t2));
    }
    printf("arm_unit: %d checks, %d failed\n%s\n", checks, failures, failures ? "" : "all checks passed");
    return failures != 0;
}
