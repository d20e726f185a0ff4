/* Kalman filters (frac/kalman.h): closed forms, the SciPy DARE fixture, bad input. */
#include <string.h>
#include "frac_test.h"
#include "frac/kalman.h"
#include "fixtures/kalman_dare_fixture.h"

#define NE KDARE_N
#define PE KDARE_P

/* Scalar random walk x+ = x + w, y = x + v: the a-priori variance obeys
 * M+ = M r / (M + r) + q, whose fixed point is M = (q + sqrt(q^2 + 4 q r)) / 2,
 * and the update gain is K = M / (M + r). */
static void test_kalman_scalar_matches_closed_form(void **state)
{
    const frac_real A = 1, C = 1, Q = 0.5, R = 2, P0 = 10, x0 = 0;
    frac_kalman_params prm;
    frac_kalman kf;
    frac_real st[FRAC_KALMAN_STORAGE(1, 1)], y;
    double M = 10.0, Kg, x = 0.0, Minf;
    int k;
    (void)state;
    prm.n = 1; prm.m = 0; prm.p = 1;
    prm.A = &A; prm.B = NULL; prm.C = &C; prm.Q = &Q; prm.R = &R; prm.P0 = &P0; prm.x0 = &x0;
    assert_int_equal(frac_kalman_init(&kf, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (k = 0; k < 60; k++) {
        y = (frac_real)(1.0 + 0.3 * sin(0.7 * k));
        /* hand recursion */
        Kg = M / (M + 2.0);
        x = x + Kg * ((double)y - x);
        assert_int_equal(frac_kalman_update(&kf, &y), FRAC_OK);
        assert_close(kf.K[0], Kg, 1e-12);
        assert_close(kf.x[0], x, 1e-12);
        assert_close(kf.P[0], (1.0 - Kg) * M, 1e-12);
        M = (1.0 - Kg) * M + 0.5;
        assert_int_equal(frac_kalman_predict(&kf, NULL), FRAC_OK);
        assert_close(kf.P[0], M, 1e-12);
    }
    Minf = (0.5 + sqrt(0.25 + 4.0 * 0.5 * 2.0)) / 2.0;
    assert_close(kf.P[0], Minf, 1e-9);
}

static frac_kalman_params dare_params(void)
{
    static frac_real A[NE * NE], B[NE], C[PE * NE], Q[NE * NE], R[PE * PE], P0[NE * NE];
    frac_kalman_params prm;
    size_t i;
    for (i = 0; i < NE * NE; i++) {
        A[i] = (frac_real)kdare_A[i];
        Q[i] = (frac_real)kdare_Q[i];
        P0[i] = (i % (NE + 1) == 0) ? FRAC_R(1.0) : FRAC_R(0.0);
    }
    for (i = 0; i < NE; i++) B[i] = (frac_real)kdare_B[i];
    for (i = 0; i < PE * NE; i++) C[i] = (frac_real)kdare_C[i];
    for (i = 0; i < PE * PE; i++) R[i] = (frac_real)kdare_R[i];
    prm.n = NE; prm.m = 1; prm.p = PE;
    prm.A = A; prm.B = B; prm.C = C; prm.Q = Q; prm.R = R; prm.P0 = P0; prm.x0 = NULL;
    return prm;
}

/* The time-varying filter converges to the steady state of the filter DARE
 * solved independently by SciPy: a-priori P equal to the fixture P and the
 * predictor gain A K equal to L = A P C^T (C P C^T + R)^-1 (thesis (7.27)). */
static void test_kalman_converges_to_scipy_dare_predictor_gain(void **state)
{
    frac_kalman_params prm = dare_params();
    frac_kalman kf;
    static frac_real st[FRAC_KALMAN_STORAGE(NE, PE)];
    frac_real y[PE] = {0, 0}, u = 0, AK[NE * PE];
    double pmax = 0.0;
    size_t i;
    int k;
    (void)state;
    assert_int_equal(frac_kalman_init(&kf, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (k = 0; k < 6000; k++) {
        assert_int_equal(frac_kalman_update(&kf, y), FRAC_OK);
        assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_OK);
    }
    frac_mat_mul(prm.A, NE, NE, kf.K, PE, AK);
    for (i = 0; i < NE * PE; i++) assert_close(AK[i], kdare_L[i], 1e-6 * (1.0 + fabs(kdare_L[i])));
    for (i = 0; i < NE * NE; i++) {
        if (fabs(kdare_P[i]) > pmax) pmax = fabs(kdare_P[i]);
    }
    for (i = 0; i < NE * NE; i++) assert_close(kf.P[i], kdare_P[i], 1e-6 * pmax);
}

/* The steady-state predictor with the fixture L and the converged
 * time-varying filter give the same a-priori estimates on the same data,
 * including the integrating disturbance state that tracks a constant
 * input disturbance (a_s = 1). */
static void test_kalman_predictor_matches_converged_filter_and_estimates_disturbance(void **state)
{
    frac_kalman_params prm = dare_params();
    frac_kalman kf;
    frac_kalman_pred kp;
    frac_kalman_pred_params pp;
    static frac_real st[FRAC_KALMAN_STORAGE(NE, PE)];
    frac_real sp[FRAC_KALMAN_PRED_STORAGE(NE, PE)], L[NE * PE], y[PE], yh[PE], u;
    double x[4] = {0, 0, 0, 0}, xn[4], z = 0.3;
    size_t i, j;
    int k;
    (void)state;
    assert_int_equal(frac_kalman_init(&kf, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    for (i = 0; i < NE * PE; i++) L[i] = (frac_real)kdare_L[i];
    pp.n = NE; pp.m = 1; pp.p = PE; pp.A = prm.A; pp.B = prm.B; pp.C = prm.C; pp.L = L; pp.e0 = NULL;
    assert_int_equal(frac_kalman_pred_init(&kp, &pp, sp, sizeof sp / sizeof sp[0]), FRAC_OK);
    /* converge the covariance first on zero data */
    y[0] = y[1] = 0;
    u = 0;
    for (k = 0; k < 6000; k++) {
        frac_kalman_update(&kf, y);
        frac_kalman_predict(&kf, &u);
    }
    /* plant: 4 states, input u - z (friction-like constant disturbance z) */
    for (k = 0; k < 20000; k++) {
        u = (frac_real)(2.0 * sin(0.01 * k));
        y[0] = (frac_real)x[0];
        y[1] = (frac_real)x[3];
        assert_int_equal(frac_kalman_update(&kf, y), FRAC_OK);
        assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_OK);
        assert_int_equal(frac_kalman_pred_step(&kp, &u, y, yh), FRAC_OK);
        for (i = 0; i < 4; i++) {
            xn[i] = kdare_B[i] * ((double)u - z);
            for (j = 0; j < 4; j++) xn[i] += kdare_A[i * NE + j] * x[j];
        }
        for (i = 0; i < 4; i++) x[i] = xn[i];
    }
    for (i = 0; i < NE; i++) assert_close(kp.e[i], kf.x[i], 1e-6 * (1.0 + fabs((double)kf.x[i])));
    /* the disturbance state has found z; the plant states are tracked */
    assert_close(kp.e[4], z, 1e-3);
    for (i = 0; i < 4; i++) assert_close(kp.e[i], x[i], 1e-3 * (1.0 + fabs(x[i])));
}

static void test_kalman_augment_disturbance_places_integrator_with_a_s_one(void **state)
{
    const frac_real A[4] = {1, 2, 3, 4}, B[2] = {5, 6}, E[2] = {-5, -6}, C[2] = {1, 0};
    frac_real Ae[9], Be[3], Ce[3];
    const frac_real wantA[9] = {1, 2, -5, 3, 4, -6, 0, 0, 1};
    size_t i;
    (void)state;
    assert_int_equal(frac_kalman_augment_disturbance(A, B, E, C, 2, 1, 1, Ae, Be, Ce), FRAC_OK);
    for (i = 0; i < 9; i++) assert_close(Ae[i], wantA[i], 0.0);
    assert_close(Be[2], 0.0, 0.0);
    assert_close(Be[1], 6.0, 0.0);
    assert_close(Ce[2], 0.0, 0.0);
    assert_int_equal(frac_kalman_augment_disturbance(A, B, E, C, FRAC_MAT_MAX, 1, 1, Ae, Be, Ce), FRAC_E_DIM);
    assert_int_equal(frac_kalman_augment_disturbance(A, NULL, E, C, 2, 1, 1, Ae, Be, Ce), FRAC_E_NULL);
}

static void test_kalman_nan_measurement_skipped_prediction_continues(void **state)
{
    frac_kalman_params prm = dare_params();
    frac_kalman kf;
    frac_kalman_pred kp;
    frac_kalman_pred_params pp;
    static frac_real st[FRAC_KALMAN_STORAGE(NE, PE)];
    frac_real sp[FRAC_KALMAN_PRED_STORAGE(NE, PE)], L[NE * PE], y[PE], u = 1, x_before[NE], P11;
    frac_real want[NE];
    size_t i;
    (void)state;
    assert_int_equal(frac_kalman_init(&kf, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    /* all components NaN: nothing changes, warning */
    y[0] = (frac_real)NAN;
    y[1] = (frac_real)NAN;
    for (i = 0; i < NE; i++) x_before[i] = kf.x[i];
    P11 = kf.P[0];
    assert_int_equal(frac_kalman_update(&kf, y), FRAC_W_MEAS_SKIPPED);
    assert_close(kf.P[0], P11, 0.0);
    /* one component NaN: the other one is used, its gain column only */
    y[0] = FRAC_R(0.1);
    y[1] = (frac_real)NAN;
    assert_int_equal(frac_kalman_update(&kf, y), FRAC_W_MEAS_SKIPPED);
    assert_true(kf.P[0] < P11);
    assert_true(kf.K[0 * PE + 0] != 0.0);
    assert_close(kf.K[0 * PE + 1], 0.0, 0.0);
    assert_true(kf.x[0] != x_before[0]);
    assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_OK);

    /* predictor: the NaN output is skipped, the model prediction goes on */
    for (i = 0; i < NE * PE; i++) L[i] = (frac_real)kdare_L[i];
    pp.n = NE; pp.m = 1; pp.p = PE; pp.A = prm.A; pp.B = prm.B; pp.C = prm.C; pp.L = L; pp.e0 = NULL;
    assert_int_equal(frac_kalman_pred_init(&kp, &pp, sp, sizeof sp / sizeof sp[0]), FRAC_OK);
    y[0] = (frac_real)NAN;
    y[1] = (frac_real)NAN;
    assert_int_equal(frac_kalman_pred_step(&kp, &u, y, NULL), FRAC_W_MEAS_SKIPPED);
    for (i = 0; i < NE; i++) want[i] = prm.B[i] * u;
    for (i = 0; i < NE; i++) assert_close(kp.e[i], want[i], 1e-15);
}

static void test_kalman_resets_covariance_on_loss_of_definiteness(void **state)
{
    frac_kalman_params prm = dare_params();
    frac_kalman kf;
    static frac_real st[FRAC_KALMAN_STORAGE(NE, PE)];
    frac_real y[PE] = {0, 0}, u = 0;
    size_t i;
    (void)state;
    assert_int_equal(frac_kalman_init(&kf, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    /* corrupt the covariance (as a radiation hit or an overflow would) */
    kf.P[2 * NE + 2] = (frac_real)NAN;
    assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_W_COV_RESET);
    for (i = 0; i < NE * NE; i++) assert_close(kf.P[i], prm.P0[i], 0.0);
    /* indefinite P: the innovation covariance is still PD, the Joseph result is not */
    for (i = 0; i < NE * NE; i++) kf.P[i] = FRAC_R(0.0);
    for (i = 0; i < NE; i++) kf.P[i * NE + i] = FRAC_R(1.0);
    kf.P[1 * NE + 1] = FRAC_R(-5.0);
    assert_int_equal(frac_kalman_update(&kf, y), FRAC_W_COV_RESET);
    for (i = 0; i < NE * NE; i++) assert_close(kf.P[i], prm.P0[i], 0.0);
    /* C P C^T + R not PD */
    kf.P[0] = FRAC_R(-1.0);
    assert_int_equal(frac_kalman_update(&kf, y), FRAC_W_COV_RESET);
    assert_close(kf.P[0], 1.0, 0.0);
    /* the filter goes on normally afterwards */
    assert_int_equal(frac_kalman_update(&kf, y), FRAC_OK);
    assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_OK);
}

static void test_kalman_rejects_bad_input_with_state_untouched(void **state)
{
    frac_kalman_params prm = dare_params();
    frac_kalman kf;
    frac_kalman_pred kp;
    frac_kalman_pred_params pp;
    static frac_real st[FRAC_KALMAN_STORAGE(NE, PE)];
    frac_real sp[FRAC_KALMAN_PRED_STORAGE(NE, PE)], L[NE * PE], y[PE] = {1, 1}, u, e_before;
    frac_real badR[PE * PE] = {1, 0, 0, -1}, x0[NE] = {1, 2, 3, 4, 5};
    frac_kalman_params bad;
    size_t i;
    (void)state;
    memset(&kf, 0, sizeof kf);
    assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_E_NOT_INIT);
    assert_int_equal(frac_kalman_init(&kf, &prm, st, FRAC_KALMAN_STORAGE(NE, PE) - 1), FRAC_E_STORAGE);
    assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_E_NOT_INIT);
    bad = prm;
    bad.R = badR;
    assert_int_equal(frac_kalman_init(&kf, &bad, st, sizeof st / sizeof st[0]), FRAC_E_NOT_POSDEF);
    bad = prm;
    bad.n = 0;
    assert_int_equal(frac_kalman_init(&kf, &bad, st, sizeof st / sizeof st[0]), FRAC_E_DIM);
    bad = prm;
    bad.B = NULL;
    assert_int_equal(frac_kalman_init(&kf, &bad, st, sizeof st / sizeof st[0]), FRAC_E_NULL);
    assert_int_equal(frac_kalman_init(NULL, &prm, st, 1), FRAC_E_NULL);
    assert_int_equal(frac_kalman_init(&kf, &prm, st, sizeof st / sizeof st[0]), FRAC_OK);
    assert_int_equal(frac_kalman_reset(&kf, x0), FRAC_OK);
    assert_close(kf.x[4], 5.0, 0.0);
    u = (frac_real)INFINITY;
    assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_E_NONFINITE);
    assert_close(kf.x[4], 5.0, 0.0);
    assert_int_equal(frac_kalman_predict(&kf, NULL), FRAC_E_NULL);
    assert_int_equal(frac_kalman_update(&kf, NULL), FRAC_E_NULL);
    x0[1] = (frac_real)NAN;
    assert_int_equal(frac_kalman_reset(&kf, x0), FRAC_E_NONFINITE);
    /* an estimate that would overflow is rejected, x and P stay */
    for (i = 0; i < NE; i++) x0[i] = (frac_real)FRAC_REAL_MAX;
    assert_int_equal(frac_kalman_reset(&kf, x0), FRAC_OK);
    u = FRAC_R(0.0);
    assert_int_equal(frac_kalman_predict(&kf, &u), FRAC_E_NUMERIC);
    assert_close(kf.x[0], FRAC_REAL_MAX, 0.0);
    for (i = 0; i < NE; i++) x0[i] = -(frac_real)FRAC_REAL_MAX;
    assert_int_equal(frac_kalman_reset(&kf, x0), FRAC_OK);
    y[0] = (frac_real)FRAC_REAL_MAX;
    y[1] = (frac_real)FRAC_REAL_MAX;
    e_before = kf.P[0];
    assert_int_equal(frac_kalman_update(&kf, y), FRAC_E_NUMERIC);
    assert_close(kf.x[0], -FRAC_REAL_MAX, 0.0);
    assert_close(kf.P[0], e_before, 0.0);
    y[0] = y[1] = FRAC_R(1.0);
    bad = prm;
    {
        frac_real Qn[NE * NE];
        for (i = 0; i < NE * NE; i++) Qn[i] = prm.Q[i];
        Qn[7] = (frac_real)INFINITY;
        bad.Q = Qn;
        assert_int_equal(frac_kalman_init(&kf, &bad, st, sizeof st / sizeof st[0]), FRAC_E_NONFINITE);
    }

    for (i = 0; i < NE * PE; i++) L[i] = (frac_real)kdare_L[i];
    pp.n = NE; pp.m = 1; pp.p = PE; pp.A = prm.A; pp.B = prm.B; pp.C = prm.C; pp.L = L; pp.e0 = NULL;
    assert_int_equal(frac_kalman_pred_init(&kp, &pp, sp, 2), FRAC_E_STORAGE);
    pp.L = NULL;
    assert_int_equal(frac_kalman_pred_init(&kp, &pp, sp, sizeof sp / sizeof sp[0]), FRAC_E_NULL);
    pp.L = L;
    L[3] = (frac_real)NAN;
    assert_int_equal(frac_kalman_pred_init(&kp, &pp, sp, sizeof sp / sizeof sp[0]), FRAC_E_NONFINITE);
    L[3] = (frac_real)kdare_L[3];
    assert_int_equal(frac_kalman_pred_init(&kp, &pp, sp, sizeof sp / sizeof sp[0]), FRAC_OK);
    u = FRAC_R(1.0);
    assert_int_equal(frac_kalman_pred_step(&kp, &u, y, NULL), FRAC_OK);
    e_before = kp.e[0];
    u = (frac_real)NAN;
    assert_int_equal(frac_kalman_pred_step(&kp, &u, y, NULL), FRAC_E_NONFINITE);
    assert_close(kp.e[0], e_before, 0.0);
    /* a measurement so large that the estimate overflows: rejected, state kept */
    u = FRAC_R(1.0);
    y[0] = (frac_real)FRAC_REAL_MAX;
    assert_int_equal(frac_kalman_pred_step(&kp, &u, y, NULL), FRAC_E_NUMERIC);
    assert_close(kp.e[0], e_before, 0.0);
    assert_int_equal(frac_kalman_pred_step(&kp, &u, NULL, NULL), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kalman_scalar_matches_closed_form),
        cmocka_unit_test(test_kalman_converges_to_scipy_dare_predictor_gain),
        cmocka_unit_test(test_kalman_predictor_matches_converged_filter_and_estimates_disturbance),
        cmocka_unit_test(test_kalman_augment_disturbance_places_integrator_with_a_s_one),
        cmocka_unit_test(test_kalman_nan_measurement_skipped_prediction_continues),
        cmocka_unit_test(test_kalman_resets_covariance_on_loss_of_definiteness),
        cmocka_unit_test(test_kalman_rejects_bad_input_with_state_untouched),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
