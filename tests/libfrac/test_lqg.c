/* State-difference LQG with delay-augmented predictor, seed 004 (6.45), (7.18)-(7.27) (frac/lqg.h). */
#include <string.h>
#include "frac_test.h"
#include "frac/lqg.h"
#include "frac/delay.h"
#include "frac/kalman.h"
#include "fixtures/lqg_fixture.h"

#define NB LQGF_NB
#define NE (LQGF_NB + 1)
#define NP LQGF_P

static frac_real fA[LQGF_N * LQGF_N], fB[LQGF_N], fC[NP * LQGF_N], fK[NB], fL[NE * NP];

static frac_lqg_params fixture_params(void)
{
    frac_lqg_params prm;
    size_t i;
    for (i = 0; i < LQGF_N * LQGF_N; i++) fA[i] = (frac_real)lqgf_A[i];
    for (i = 0; i < LQGF_N; i++) fB[i] = (frac_real)lqgf_B[i];
    for (i = 0; i < NP * LQGF_N; i++) fC[i] = (frac_real)lqgf_C[i];
    for (i = 0; i < NB; i++) fK[i] = (frac_real)lqgf_K[i];
    for (i = 0; i < NE * NP; i++) fL[i] = (frac_real)lqgf_L[i];
    prm.n = LQGF_N;
    prm.d_i = LQGF_DI;
    prm.p = NP;
    prm.d_o = lqgf_d_o;
    prm.A = fA;
    prm.B = fB;
    prm.C = fC;
    prm.K = fK;
    prm.L = fL;
    return prm;
}

/* dense reference: (7.18) by frac_delay_augment, (7.26) by frac_kalman_augment_disturbance,
 * (7.27) by frac_kalman_pred */
static frac_real dA[NB * NB], dB[NB], dE[NB], dC[NP * NB], dAe[NE * NE], dBe[NE], dCe[NP * NE];

static void dense_reference(frac_kalman_pred *kp, frac_real *st, size_t len)
{
    frac_kalman_pred_params pp;
    assert_int_equal(frac_delay_augment(fA, fB, fC, LQGF_N, LQGF_DI, NP, lqgf_d_o, dA, dB, dE, dC), FRAC_OK);
    assert_int_equal(frac_kalman_augment_disturbance(dA, dB, dE, dC, NB, 1, NP, dAe, dBe, dCe), FRAC_OK);
    pp.n = NE; pp.m = 1; pp.p = NP; pp.A = dAe; pp.B = dBe; pp.C = dCe; pp.L = fL; pp.e0 = NULL;
    assert_int_equal(frac_kalman_pred_init(kp, &pp, st, len), FRAC_OK);
}

static frac_real dense_law(const frac_kalman_pred *kp, frac_real u_star)
{
    frac_real fb = FRAC_R(0.0);
    size_t i;
    for (i = 0; i < NB; i++) fb += fK[i] * kp->e[i];
    return u_star + fb - kp->e[NB];
}

/* The structured step equals the law (7.21) plus the dense predictor (7.27)
 * on the matrices built from (7.18)/(7.26), for arbitrary signals, also
 * when measurements are missing. */
static void test_lqg_structured_step_equals_dense_augmented_predictor(void **state)
{
    frac_lqg_params prm = fixture_params();
    frac_lqg c;
    frac_kalman_pred kp;
    frac_real st[FRAC_LQG_STORAGE(NE, NP)], sp[FRAC_KALMAN_PRED_STORAGE(NE, NP)];
    frac_real yref[NP], y[NP], ey[NP], u, eu, ud;
    int k, st_c, st_d;
    size_t i;
    (void)state;
    assert_int_equal(frac_lqg_init(&c, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    dense_reference(&kp, sp, sizeof sp / sizeof sp[0]);
    for (k = 0; k < 300; k++) {
        frac_real ustar = (frac_real)(0.3 * sin(0.05 * k));
        yref[0] = (frac_real)(0.01 * k);
        yref[1] = (frac_real)(0.2 * cos(0.02 * k));
        y[0] = (frac_real)(0.01 * k - 0.02 * sin(0.11 * k));
        y[1] = (k % 17 == 5) ? (frac_real)NAN : (frac_real)(0.1 * sin(0.07 * k));
        ud = dense_law(&kp, ustar);
        st_c = frac_lqg_step(&c, ustar, yref, y, &u);
        assert_close(u, ud, 1e-12);
        eu = ustar - ud;
        for (i = 0; i < NP; i++) ey[i] = yref[i] - y[i];
        st_d = frac_kalman_pred_step(&kp, &eu, ey, NULL);
        assert_int_equal(st_c, st_d);
        assert_int_equal(st_c, (k % 17 == 5) ? FRAC_W_MEAS_SKIPPED : FRAC_OK);
        for (i = 0; i < NE; i++) assert_close(c.e[i], kp.e[i], 1e-10 * (1.0 + fabs((double)kp.e[i])));
    }
}

/* The same agreement at the thesis Exp. D size (notes 004b check 17):
 * n = 16, d_i = 4, d_o = 3 on y_3, 23 + 1 states, K 1 x 23, L 24 x 3,
 * with arbitrary (deterministic) matrices. */
static void test_lqg_exp_d_dimensions_structured_equals_dense(void **state)
{
    enum { N = 16, P = 3, NBD = 23, NED = 24 };
    static const size_t d_o[P] = {0, 0, 3};
    static frac_real A[N * N], B[N], C[P * N], K[NBD], L[NED * P];
    static frac_real Ab[NBD * NBD], Bb[NBD], Eb[NBD], Cb[P * NBD], Ae[NED * NED], Be[NED], Ce[P * NED];
    frac_real st[FRAC_LQG_STORAGE(NED, P)], sp[FRAC_KALMAN_PRED_STORAGE(NED, P)];
    frac_real yref[P], y[P], ey[P], u, ud, eu, fb;
    frac_lqg_params prm;
    frac_kalman_pred_params pp;
    frac_lqg c;
    frac_kalman_pred kp;
    unsigned long s = 99;
    size_t i;
    int k;
    (void)state;
    for (i = 0; i < N * N; i++) {
        s = s * 1103515245UL + 12345UL;
        A[i] = (frac_real)(((double)((s >> 8) % 2001) - 1000.0) * 4e-5);
    }
    for (i = 0; i < N; i++) {
        A[i * N + i] += FRAC_R(0.9);
        B[i] = (frac_real)(0.01 * (double)(i % 5));
    }
    for (i = 0; i < P * N; i++) C[i] = (frac_real)((i % 7 == 0) ? 1.0 : 0.01 * (double)(i % 3));
    for (i = 0; i < NBD; i++) K[i] = (frac_real)(-0.02 * (double)(i % 4));
    for (i = 0; i < NED * P; i++) L[i] = (frac_real)(0.03 * (double)((i * 7) % 5) - 0.05);
    prm.n = N; prm.d_i = 4; prm.p = P; prm.d_o = d_o;
    prm.A = A; prm.B = B; prm.C = C; prm.K = K; prm.L = L;
    assert_int_equal(frac_delay_aug_order(N, 4, P, d_o), NBD);
    assert_int_equal(frac_lqg_init(&c, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_delay_augment(A, B, C, N, 4, P, d_o, Ab, Bb, Eb, Cb), FRAC_OK);
    assert_int_equal(frac_kalman_augment_disturbance(Ab, Bb, Eb, Cb, NBD, 1, P, Ae, Be, Ce), FRAC_OK);
    pp.n = NED; pp.m = 1; pp.p = P; pp.A = Ae; pp.B = Be; pp.C = Ce; pp.L = L; pp.e0 = NULL;
    assert_int_equal(frac_kalman_pred_init(&kp, &pp, sp, sizeof sp / sizeof sp[0]), FRAC_OK);
    for (k = 0; k < 200; k++) {
        for (i = 0; i < P; i++) {
            yref[i] = (frac_real)sin(0.03 * k + (double)i);
            y[i] = (frac_real)(0.9 * sin(0.03 * k + (double)i) + 0.01 * cos(0.2 * k));
        }
        fb = FRAC_R(0.0);
        for (i = 0; i < NBD; i++) fb += K[i] * kp.e[i];
        ud = FRAC_R(0.2) + fb - kp.e[NBD];
        assert_int_equal(frac_lqg_step(&c, FRAC_R(0.2), yref, y, &u), FRAC_OK);
        assert_close(u, ud, 1e-10);
        eu = FRAC_R(0.2) - ud;
        for (i = 0; i < P; i++) ey[i] = yref[i] - y[i];
        assert_int_equal(frac_kalman_pred_step(&kp, &eu, ey, NULL), FRAC_OK);
        for (i = 0; i < NED; i++) assert_close(c.e[i], kp.e[i], 1e-10 * (1.0 + fabs((double)kp.e[i])));
    }
}

/* Closed loop: plant between the real shift registers (d_i = 4 on the
 * torque, d_o = 3 on omega), constant friction torque z at the input.
 * The SciPy-designed LQG brings theta to the reference and its
 * disturbance state estimates the friction: e_z -> -z, so the law adds +z. */
static void test_lqg_closed_loop_with_delays_rejects_constant_friction(void **state)
{
    frac_lqg_params prm = fixture_params();
    frac_lqg c;
    frac_delay_regs regs;
    frac_delayline lines[NP];
    frac_real st[FRAC_LQG_STORAGE(NE, NP)], in_st[LQGF_DI], out_st[3];
    frac_real x[2] = {0, 0}, xn[2], y[NP], yb[NP], yref[NP], ubar = 0, u;
    const frac_real z = FRAC_R(0.5);
    int k;
    (void)state;
    assert_int_equal(frac_lqg_init(&c, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_delay_regs_init(&regs, LQGF_DI, in_st, NP, lqgf_d_o, lines, out_st), FRAC_OK);
    yref[0] = FRAC_R(1.0); /* theta* = 1 rad, at rest: u* = 0 */
    yref[1] = FRAC_R(0.0);
    for (k = 0; k < 6000; k++) {
        /* measurements of sample k, as the controller receives them */
        y[0] = x[0];
        y[1] = x[1];
        frac_delay_regs_output(&regs, y, yb);
        assert_true(frac_lqg_step(&c, FRAC_R(0.0), yref, yb, &ubar) == FRAC_OK);
        /* the drive applies the command d_i samples later */
        frac_delay_regs_input(&regs, ubar, &u);
        xn[0] = fA[0] * x[0] + fA[1] * x[1] + fB[0] * (u - z);
        xn[1] = fA[2] * x[0] + fA[3] * x[1] + fB[1] * (u - z);
        x[0] = xn[0];
        x[1] = xn[1];
    }
    assert_close(x[0], 1.0, 1e-6);
    assert_close(x[1], 0.0, 1e-6);
    assert_close(ubar, 0.5, 1e-6);
    assert_close(frac_lqg_friction_estimate(&c), 0.5, 1e-6);
}

static void test_lqg_bad_reference_rejected_with_state_untouched(void **state)
{
    frac_lqg_params prm = fixture_params();
    frac_lqg c;
    frac_real st[FRAC_LQG_STORAGE(NE, NP)], e_before[NE];
    frac_real yref[NP] = {1, 0}, y[NP] = {0, 0}, u, u_last;
    size_t i;
    (void)state;
    assert_int_equal(frac_lqg_init(&c, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (i = 0; i < 5; i++) frac_lqg_step(&c, FRAC_R(0.1), yref, y, &u);
    u_last = u;
    for (i = 0; i < NE; i++) e_before[i] = c.e[i];
    assert_int_equal(frac_lqg_step(&c, (frac_real)NAN, yref, y, &u), FRAC_E_NONFINITE);
    assert_close(u, u_last, 0.0);
    yref[1] = (frac_real)INFINITY;
    u = 123;
    assert_int_equal(frac_lqg_step(&c, FRAC_R(0.1), yref, y, &u), FRAC_E_NONFINITE);
    assert_close(u, u_last, 0.0);
    for (i = 0; i < NE; i++) assert_close(c.e[i], e_before[i], 0.0);
    yref[1] = FRAC_R(0.0);
    yref[0] = -(frac_real)FRAC_REAL_MAX; /* finite inputs, overflowing innovation */
    y[0] = (frac_real)FRAC_REAL_MAX;
    assert_int_equal(frac_lqg_step(&c, FRAC_R(0.1), yref, y, &u), FRAC_E_NUMERIC);
    for (i = 0; i < NE; i++) assert_close(c.e[i], e_before[i], 0.0);
    assert_close(u, u_last, 0.0);
    assert_int_equal(frac_lqg_step(&c, FRAC_R(0.1), yref, NULL, &u), FRAC_E_NULL);
    assert_int_equal(frac_lqg_reset(&c), FRAC_OK);
    assert_close(frac_lqg_friction_estimate(&c), 0.0, 0.0);
}

static void test_lqg_init_rejects_bad_parameters(void **state)
{
    frac_lqg_params prm = fixture_params(), bad;
    frac_lqg c;
    frac_real st[FRAC_LQG_STORAGE(NE, NP)], u, y[NP] = {0, 0};
    size_t big_d[NP] = {0, FRAC_MAT_MAX};
    (void)state;
    memset(&c, 0, sizeof c);
    assert_int_equal(frac_lqg_step(&c, 0, y, y, &u), FRAC_E_NOT_INIT);
    assert_int_equal(frac_lqg_reset(&c), FRAC_E_NOT_INIT);
    assert_close(frac_lqg_friction_estimate(&c), 0.0, 0.0);
    assert_int_equal(frac_lqg_init(&c, &prm, st, FRAC_LQG_STORAGE(NE, NP) - 1), FRAC_E_STORAGE);
    bad = prm;
    bad.d_o = big_d;
    assert_int_equal(frac_lqg_init(&c, &bad, st, sizeof st / sizeof st[0]), FRAC_E_DIM);
    bad = prm;
    bad.p = 0;
    assert_int_equal(frac_lqg_init(&c, &bad, st, sizeof st / sizeof st[0]), FRAC_E_DIM);
    bad = prm;
    bad.L = NULL;
    assert_int_equal(frac_lqg_init(&c, &bad, st, sizeof st / sizeof st[0]), FRAC_E_NULL);
    fK[2] = (frac_real)NAN;
    assert_int_equal(frac_lqg_init(&c, &prm, st, sizeof st / sizeof st[0]), FRAC_E_NONFINITE);
    assert_int_equal(frac_lqg_init(NULL, &prm, st, 1), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lqg_structured_step_equals_dense_augmented_predictor),
        cmocka_unit_test(test_lqg_exp_d_dimensions_structured_equals_dense),
        cmocka_unit_test(test_lqg_closed_loop_with_delays_rejects_constant_friction),
        cmocka_unit_test(test_lqg_bad_reference_rejected_with_state_untouched),
        cmocka_unit_test(test_lqg_init_rejects_bad_parameters),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
