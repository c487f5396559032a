/* SPDX-License-Identifier: BSD-2-Clause */
/* rod.c's event update on states placed exactly on a switching surface, which
 * no importer reaches on purpose but round-off does: the state must leave the
 * surface to the side the mode lives on, by moving a state the indicator
 * depends on. Built by tests/c/CMakeLists.txt, run by tests/fmu/test_c_robustness.py;
 * exit status 0 only if every check passed. */
#include <math.h>
#include <stdio.h>

#include "rod.h"
#include "unit_check.h"

/* The core's event indicators on the rod. */
static void indicators(const RodParams *p, ContactMode m, const double x[ROD_NX], double z[CONTACT_NZ])
{
    const Contact c = rod_contact(p);
    contact_event_indicators(&c, m, x, z);
}

/* A sticking state with the forward fold a + q_+ F_N exactly 0: y is walked
 * ulp by ulp from the fold's root until the indicator, as rod.c computes it,
 * is 0. False if no such double lies near. */
static bool on_forward_fold(const RodParams *p, double x[ROD_NX])
{
    const ContactMode stick = { true, 0 };
    const RodCoeffs k = rod_coeffs(p, x[ROD_THETA], x[ROD_PHI]);
    /* F_N = -y/eps^2 (delta = 0), so a + q_+ F_N = 0 at y = a eps^2 / q_+. */
    x[ROD_Y] = k.a * p->epsilon * p->epsilon / k.q_plus;
    double z[CONTACT_NZ];
    for (int i = 0; i < 64; ++i) {
        indicators(p, stick, x, z);
        if (z[CONTACT_Z_SLIP] == 0) return true;
        x[ROD_Y] = nextafter(x[ROD_Y], z[CONTACT_Z_SLIP] > 0 ? 0 : -INFINITY);
    }
    return false;
}

static void test_a_stuck_rod_on_its_fold_leaves_into_the_stick_by_moving_what_the_fold_depends_on(void)
{
    const RodParams p = { .alpha = 3, .mu = 3, .delta = 0, .epsilon = 1e-3 };
    int found = 0;
    for (double theta = 0.6; theta < 1.4; theta += 0.1) {
        double x[ROD_NX] = { [ROD_V] = 0, [ROD_W] = 1e-4, [ROD_THETA] = theta, [ROD_PHI] = 0.8 };
        if (!on_forward_fold(&p, x)) continue;
        ++found;
        const double before[ROD_NX] = { x[0], x[1], x[2], x[3], x[4], x[5] };
        bool moved = false;
        const Contact c = rod_contact(&p);
        CHECK(contact_move_off_surfaces(&c, (ContactMode){ true, 0 }, x, (ContactSurfaces){ 0 }, 1, &moved),
              "theta = %g: search failed", theta);
        double z[CONTACT_NZ];
        indicators(&p, (ContactMode){ true, 0 }, x, z);
        CHECK(moved && z[CONTACT_Z_SLIP] < 0, "theta = %g: fold indicator %g after the move, wanted < 0", theta,
              z[CONTACT_Z_SLIP]);
        /* v and w do not enter a + q_+ F_N when delta = 0: moving them cannot leave the fold. */
        CHECK(x[ROD_V] == before[ROD_V] && x[ROD_W] == before[ROD_W], "theta = %g: moved v or w", theta);
        double largest = 0;
        for (int i = 0; i < ROD_NX; ++i) largest = fmax(largest, fabs(x[i] - before[i]) / fmax(fabs(before[i]), 1e-300));
        CHECK(largest < 1e-9, "theta = %g: moved by %g relative, not a nudge", theta, largest);
    }
    CHECK(found >= 3, "only %d of 8 angles have a double exactly on the fold", found);
}

/* The largest rate |lambda| of y'' = -P (y/eps^2 + delta w/eps), one mode's normal motion on the
 * linear law with P its response (p_+, p_-, S_w): lambda^2 + (delta P/eps) lambda + P/eps^2 = 0. */
static double fastest_rate(double P, double delta, double eps)
{
    const double b = delta * P / eps, c = P / (eps * eps), disc = b * b / 4 - c;
    return disc >= 0 ? fabs(b) / 2 + sqrt(disc) : sqrt(c);   /* real roots, or a complex pair of modulus sqrt(c) */
}

static void test_the_contacts_time_scale_is_its_fastest_modes_rate(void)
{
    /* contact_time_scale bounds 1/|lambda| of the fastest mode from below by the rates of the
     * paper's coefficients (rod.c's formulas), within the factor 3 its bound |b| + sqrt|c| allows. */
    for (double delta = 0; delta <= 100; delta = delta ? 10 * delta : 0.01)
        for (double theta = 0.1; theta < 3; theta += 0.4) {
            const RodParams p = { .alpha = 3, .mu = 2, .delta = delta, .epsilon = 1e-4 };
            const RodCoeffs k = rod_coeffs(&p, theta, 0.7);
            double fastest = 0;
            const double P[] = { k.p_plus, k.p_minus, k.S_w };
            for (int i = 0; i < 3; ++i) fastest = fmax(fastest, fastest_rate(fabs(P[i]), delta, p.epsilon));
            for (double y = 0; y <= 1e-3; y += 1e-3) {   /* touching, and in flight: the law's touch-down slopes */
                const double x[ROD_NX] = { [ROD_Y] = y, [ROD_W] = -0.1, [ROD_THETA] = theta, [ROD_PHI] = 0.7 };
                const Contact c = rod_contact(&p);
                const double tau = contact_time_scale(&c, x);
                CHECK(tau <= 1 / fastest * (1 + 1e-12) && tau >= 1 / (3 * fastest),
                      "delta = %g, theta = %g, y = %g: time scale %g, fastest mode's 1/rate %g", delta, theta, y, tau,
                      1 / fastest);
            }
        }
}

/* In flight above the floor the contact indicator stays negative however fast the rod falls:
 * h = -y/eps - delta w alone would cross 0 at y = -eps delta w > 0, where nothing switches. */
static void test_the_flight_indicator_does_not_cross_above_the_floor(void)
{
    const RodParams p = { .alpha = 3, .mu = 3, .delta = 1, .epsilon = 1e-3 };
    const ContactMode flight = { false, +1 };
    for (double y = 1e-12; y < 1; y *= 10)
        for (double w = -1e3; w < 0; w /= 10) {
            const double x[ROD_NX] = { [ROD_Y] = y, [ROD_W] = w, [ROD_V] = 1, [ROD_THETA] = 1, [ROD_PHI] = 0.5 };
            double z[CONTACT_NZ];
            indicators(&p, flight, x, z);
            CHECK(z[CONTACT_Z_FORCE] < 0, "y = %g, w = %g: flight's contact indicator %g, wanted < 0", y, w,
                  z[CONTACT_Z_FORCE]);
        }
}

/* A contact on F_N = 0 where an integrator located it (h a little below 0, as a root finder
 * overshoots) continues exactly when the free motion would at once re-enter it: the sign of
 * h' = -w/eps - delta b of the linear law, with b of eq coeffs. */
static void test_a_located_lift_off_is_decided_by_the_free_motions_h_rate(void)
{
    int kept = 0, left = 0;
    for (double phi = 0; phi < 3; phi += 0.25)
        for (double w = 1e-4; w < 1; w *= 3) {
            const RodParams p = { .alpha = 3, .mu = 0.2, .delta = 2, .epsilon = 1e-3 };
            const double eps = p.epsilon, theta = 1.0;
            /* in the floor, rising, with h = -y/eps - delta w = -1e-12: just past F_N = 0 */
            const double y = -eps * (p.delta * w - 1e-12);
            double x[ROD_NX] = { [ROD_Y] = y, [ROD_W] = w, [ROD_V] = 1, [ROD_THETA] = theta, [ROD_PHI] = phi };
            const double b = -1 + phi * phi * sin(theta);   /* eq coeffs */
            const double h_rate = -w / eps - p.delta * b;
            if (fabs(h_rate) < 1e-6 * (w / eps)) continue;
            const Contact c = rod_contact(&p);
            bool changed;
            const ContactMode m = contact_decide_mode(&c, (ContactMode){ true, +1 }, x,
                                                      (ContactSurfaces){ .force = true }, &changed);
            CHECK(m.contact == (h_rate > 0), "phi = %g, w = %g: h' = %g, contact %d", phi, w, h_rate, m.contact);
            kept += m.contact;
            left += !m.contact;
            /* not located, the same state is clearly past the surface: it lifts off */
            const ContactMode plain = contact_decide_mode(&c, (ContactMode){ true, +1 }, x, (ContactSurfaces){ 0 },
                                                          &changed);
            CHECK(!plain.contact, "phi = %g, w = %g: a state past F_N = 0 kept its contact", phi, w);
        }
    CHECK(kept >= 5 && left >= 5, "the cases did not cover both outcomes: kept %d, left %d", kept, left);
}

/* The fast normal motion grows exactly in the slips whose p_s is negative (the paradox). */
static void test_fast_growth_is_the_slips_with_negative_p(void)
{
    const RodParams p = { .alpha = 3, .mu = 3, .delta = 1, .epsilon = 1e-3 };
    const Contact c = rod_contact(&p);
    int grows = 0;
    for (double theta = 0.05; theta < 3.1; theta += 0.1) {
        const double x[ROD_NX] = { [ROD_Y] = -1e-6, [ROD_THETA] = theta, [ROD_PHI] = 0.3 };
        const RodCoeffs k = rod_coeffs(&p, theta, 0.3);
        CHECK(contact_fast_growth(&c, (ContactMode){ true, +1 }, x) == (k.p_plus < 0), "theta = %g: slip +1", theta);
        CHECK(contact_fast_growth(&c, (ContactMode){ true, -1 }, x) == (k.p_minus < 0), "theta = %g: slip -1", theta);
        CHECK(!contact_fast_growth(&c, (ContactMode){ true, 0 }, x) && !contact_fast_growth(&c, (ContactMode){ false, +1 }, x),
              "theta = %g: stick or flight grows", theta);
        grows += k.p_plus < 0;
    }
    CHECK(grows >= 3, "only %d angles in the Painleve wedge", grows);
}

/* In flight no friction acts, so v = 0 switches nothing and is no event; a contact entered
 * from flight slips the way v points, whatever label the flight carried. */
static void test_a_contact_entered_from_flight_slips_the_way_v_points(void)
{
    const RodParams p = { .alpha = 3, .mu = 0.3, .delta = 1, .epsilon = 1e-3 };
    const Contact c = rod_contact(&p);
    for (double v = -1; v <= 1; v += 0.5) {
        if (v == 0) continue;
        for (int label = -1; label <= 1; label += 2) {
            double x[ROD_NX] = { [ROD_Y] = -1e-9, [ROD_W] = -0.5, [ROD_V] = v, [ROD_THETA] = 1, [ROD_PHI] = 0.5 };
            double z[CONTACT_NZ];
            indicators(&p, (ContactMode){ false, label }, x, z);
            CHECK(z[CONTACT_Z_SLIP] > 0, "v = %g: flight's slip indicator %g", v, z[CONTACT_Z_SLIP]);
            bool changed;
            const ContactMode m = contact_decide_mode(&c, (ContactMode){ false, label }, x, (ContactSurfaces){ 0 },
                                                      &changed);
            CHECK(m.contact && m.slip == (v > 0 ? +1 : -1) && !changed, "v = %g, label %+d: contact %d, slip %+d",
                  v, label, m.contact, m.slip);
        }
    }
}

int main(void)
{
    test_a_stuck_rod_on_its_fold_leaves_into_the_stick_by_moving_what_the_fold_depends_on();
    test_the_contacts_time_scale_is_its_fastest_modes_rate();
    test_the_flight_indicator_does_not_cross_above_the_floor();
    test_a_located_lift_off_is_decided_by_the_free_motions_h_rate();
    test_fast_growth_is_the_slips_with_negative_p();
    test_a_contact_entered_from_flight_slips_the_way_v_points();
    printf("rod_unit: %d checks, %s\n", checks, failures ? "FAILED" : "all checks passed");
    return failures != 0;
}
