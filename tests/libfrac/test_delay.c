/* Delay models, seed 004 Sec. 7.3-7.5 (frac/delay.h). */
#include "frac_test.h"
#include "frac/delay.h"

/* a small 3-state plant with 3 outputs (as theta_M, dtheta_M, dpsi_L) */
static const frac_real PA[9] = {0.9, 0.1, 0.0, -0.2, 0.8, 0.05, 0.0, 0.3, 0.7};
static const frac_real PB[3] = {0.0, 0.5, 0.1};
static const frac_real PC[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

static void test_delay_registers_impulse_u_is_ubar_delayed_4_and_y3_delayed_3(void **state)
{
    frac_delay_regs r;
    frac_delayline lines[3];
    frac_real in_st[4], out_st[3], u, y[3], yb[3];
    const size_t d_o[3] = {0, 0, 3};
    int k;
    (void)state;
    assert_int_equal(frac_delay_regs_init(&r, 4, in_st, 3, d_o, lines, out_st), FRAC_OK);
    for (k = 0; k < 12; k++) {
        /* u_bar = delta[k]; y_j = delta[k] on every output */
        assert_int_equal(frac_delay_regs_input(&r, k == 0 ? FRAC_R(1.0) : FRAC_R(0.0), &u), FRAC_OK);
        assert_close(u, k == 4 ? 1.0 : 0.0, 0.0); /* u[k] = u_bar[k - 4] (7.8) */
        y[0] = y[1] = y[2] = (k == 0) ? FRAC_R(1.0) : FRAC_R(0.0);
        assert_int_equal(frac_delay_regs_output(&r, y, yb), FRAC_OK);
        assert_close(yb[0], k == 0 ? 1.0 : 0.0, 0.0);
        assert_close(yb[1], k == 0 ? 1.0 : 0.0, 0.0);
        assert_close(yb[2], k == 3 ? 1.0 : 0.0, 0.0); /* y3_bar[k] = y3[k - 3] (7.13) */
    }
}

static void test_delay_augmented_model_dimensions_exp_d(void **state)
{
    const size_t d_o[3] = {0, 0, 3};
    (void)state;
    assert_int_equal(frac_delay_aug_order(16, 4, 3, d_o), 23);
    assert_int_equal(frac_delay_aug_order(40, 4, 3, d_o), 47);
    assert_int_equal(frac_delay_aug_order(16, 0, 3, NULL), 16);
}

/* Simulating (7.18) with u_bar = delta[k] (notes 004b check 20): the applied
 * input xi_1 is u_bar[k-4], and the augmented outputs equal the undelayed
 * plant driven by u[k] = u_bar[k - 4], with output 3 read 3 samples late;
 * for any input, (7.18) equals the plant between the two shift registers. */
static void test_delay_augmented_model_equals_plant_between_shift_registers(void **state)
{
    const size_t d_o[3] = {0, 0, 3};
    frac_real Ab[10 * 10], Bb[10], Eb[10], Cb[3 * 10];
    frac_real xb[10] = {0}, xbn[10], yb_aug[3];
    frac_real x[3] = {0}, xn[3], y[3], yb_reg[3], u;
    frac_delay_regs r;
    frac_delayline lines[3];
    frac_real in_st[4], out_st[3];
    int k, j;
    (void)state;
    assert_int_equal(frac_delay_augment(PA, PB, PC, 3, 4, 3, d_o, Ab, Bb, Eb, Cb), FRAC_OK);
    assert_int_equal(frac_delay_regs_init(&r, 4, in_st, 3, d_o, lines, out_st), FRAC_OK);
    for (k = 0; k < 40; k++) {
        frac_real ubar = (k == 0) ? FRAC_R(1.0) : (k > 10 ? (frac_real)sin(0.3 * k) : FRAC_R(0.0));
        /* augmented: outputs of sample k, then the state update */
        frac_mat_vec(Cb, 3, 10, xb, yb_aug);
        if (k <= 10) assert_close(xb[3], k == 4 ? 1.0 : 0.0, 0.0); /* xi_1 = u[k] = u_bar[k-4] */
        frac_mat_vec(Ab, 10, 10, xb, xbn);
        for (j = 0; j < 10; j++) xb[j] = xbn[j] + Bb[j] * ubar;
        /* plant between registers */
        frac_delay_regs_input(&r, ubar, &u);
        frac_mat_vec(PC, 3, 3, x, y);
        frac_delay_regs_output(&r, y, yb_reg);
        frac_mat_vec(PA, 3, 3, x, xn);
        for (j = 0; j < 3; j++) x[j] = xn[j] + PB[j] * u;
        for (j = 0; j < 3; j++) assert_close(yb_aug[j], yb_reg[j], 1e-12);
    }
}

static void test_delay_disturbance_enters_at_chain_input_with_minus_sign(void **state)
{
    const size_t d_o[3] = {0, 0, 3};
    frac_real Ab[100], Bb[10], Eb[10], Cb[30];
    frac_real A0[9], B0[3], E0[3], C0[9];
    int i;
    (void)state;
    frac_delay_augment(PA, PB, PC, 3, 4, 3, d_o, Ab, Bb, Eb, Cb);
    for (i = 0; i < 10; i++) assert_close(Eb[i], -Bb[i], 0.0);
    assert_close(Bb[6], 1.0, 0.0); /* xi_4 is state 3 + 3 */
    /* no input delay: B_bar = B', E_bar = -B', C_bar = C' */
    assert_int_equal(frac_delay_augment(PA, PB, PC, 3, 0, 3, NULL, A0, B0, E0, C0), FRAC_OK);
    for (i = 0; i < 3; i++) {
        assert_close(B0[i], PB[i], 0.0);
        assert_close(E0[i], -PB[i], 0.0);
    }
    for (i = 0; i < 9; i++) {
        assert_close(A0[i], PA[i], 0.0);
        assert_close(C0[i], PC[i], 0.0);
    }
}

static void test_delay_bad_input(void **state)
{
    const size_t d_o[3] = {0, 0, FRAC_MAT_MAX};
    frac_real Ab[4], Bb[2], Cb[6], in_st[2], out_st[1], u, y[3] = {1, 2, 3}, yb[3];
    frac_delay_regs r;
    frac_delayline lines[3];
    const size_t d1[3] = {0, 0, 1};
    (void)state;
    assert_int_equal(frac_delay_augment(PA, PB, PC, 3, 4, 3, d_o, Ab, Bb, NULL, Cb), FRAC_E_DIM);
    assert_int_equal(frac_delay_augment(PA, PB, PC, 3, 4, 0, NULL, Ab, Bb, NULL, Cb), FRAC_E_DIM);
    assert_int_equal(frac_delay_augment(NULL, PB, PC, 3, 4, 3, NULL, Ab, Bb, NULL, Cb), FRAC_E_NULL);
    assert_int_equal(frac_delay_regs_init(&r, 2, in_st, 0, NULL, lines, NULL), FRAC_E_DIM);
    assert_int_equal(frac_delay_regs_input(&r, FRAC_R(1.0), &u), FRAC_E_NOT_INIT);
    assert_int_equal(frac_delay_regs_init(&r, 2, NULL, 3, NULL, lines, NULL), FRAC_E_NULL);
    assert_int_equal(frac_delay_regs_init(&r, 2, in_st, 3, d1, lines, out_st), FRAC_OK);
    frac_delay_regs_input(&r, FRAC_R(5.0), &u);
    frac_delay_regs_input(&r, FRAC_R(6.0), &u);
    frac_delay_regs_input(&r, FRAC_R(7.0), &u);
    assert_close(u, 5.0, 0.0);
    assert_int_equal(frac_delay_regs_input(&r, (frac_real)NAN, &u), FRAC_E_NONFINITE);
    assert_close(u, 5.0, 0.0);
    frac_delay_regs_input(&r, FRAC_R(8.0), &u);
    assert_close(u, 6.0, 0.0); /* the NaN never entered the register */
    frac_delay_regs_output(&r, y, yb);
    y[1] = (frac_real)NAN;
    y[2] = FRAC_R(9.0);
    assert_int_equal(frac_delay_regs_output(&r, y, yb), FRAC_E_NONFINITE);
    assert_close(yb[1], 2.0, 0.0);
    assert_close(yb[2], 3.0, 0.0);
    assert_int_equal(frac_delay_regs_output(&r, NULL, yb), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_delay_registers_impulse_u_is_ubar_delayed_4_and_y3_delayed_3),
        cmocka_unit_test(test_delay_augmented_model_dimensions_exp_d),
        cmocka_unit_test(test_delay_augmented_model_equals_plant_between_shift_registers),
        cmocka_unit_test(test_delay_disturbance_enters_at_chain_input_with_minus_sign),
        cmocka_unit_test(test_delay_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
