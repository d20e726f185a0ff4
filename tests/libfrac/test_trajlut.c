/* Multi-channel trajectory playback with lead/lag, seed 004 Sec. 8.6 (frac/trajlut.h). */
#include <string.h>
#include "frac_test.h"
#include "frac/trajlut.h"
#include "frac/traj.h"

#define NS 200
#define TS 1.2e-3

static frac_real ch_theta[NS], ch_dtheta[NS], ch_dpsi[NS], ch_tau[NS];

/* channels: theta_M*, dtheta_M*, dpsi_L*, tau_M*; distinct values per sample */
static frac_trajlut_params make_params(const frac_real *const *data, const long *lead)
{
    frac_trajlut_params p;
    int i;
    for (i = 0; i < NS; i++) {
        ch_theta[i] = (frac_real)(0.001 * i * i);
        ch_dtheta[i] = (frac_real)(0.002 * i);
        ch_dpsi[i] = (frac_real)sin(0.05 * i);
        ch_tau[i] = (frac_real)(10.0 + i);
    }
    p.channels = 4;
    p.n = NS;
    p.data = data;
    p.t0 = FRAC_R(0.0);
    p.dt = FRAC_R(TS);
    p.Ts = FRAC_R(TS);
    p.lead = lead;
    p.t_motion_start = FRAC_R(50 * TS);
    p.t_motion_end = FRAC_R(150 * TS);
    p.interp = FRAC_LUT_LINEAR;
    return p;
}

/* notes 004b check 21: u_bar*[k] = u*[k + 4], y_bar_3*[k] = y_3*[k - 3], encoder refs unshifted */
static void test_trajlut_torque_leads_4_and_imu_reference_lags_3(void **state)
{
    const frac_real *const data[4] = {ch_theta, ch_dtheta, ch_dpsi, ch_tau};
    const long lead[4] = {0, 0, -3, 4};
    frac_trajlut_params p = make_params(data, lead);
    frac_trajlut tl;
    frac_real out[4];
    int k, seg;
    (void)state;
    assert_int_equal(frac_trajlut_init(&tl, &p, NULL), FRAC_OK);
    /* the lagged channel starts outside the table, the leading one ends outside */
    for (k = 0; k < NS; k++) {
        assert_int_equal(frac_trajlut_step(&tl, out, &seg), (k < 3 || k + 4 > NS - 1) ? FRAC_W_CLAMPED : FRAC_OK);
    }
    for (k = 3; k < NS - 4; k++) {
        assert_int_equal(frac_trajlut_eval(&tl, (unsigned long)k, out, &seg), FRAC_OK);
        assert_close(out[0], ch_theta[k], 1e-9);
        assert_close(out[1], ch_dtheta[k], 1e-9);
        assert_close(out[2], ch_dpsi[k - 3], 1e-9);
        assert_close(out[3], ch_tau[k + 4], 1e-9);
    }
}

static void test_trajlut_segments_and_clamped_rest_outside_table(void **state)
{
    const frac_real *const data[4] = {ch_theta, ch_dtheta, ch_dpsi, ch_tau};
    const long lead[4] = {0, 0, -3, 4};
    frac_trajlut_params p = make_params(data, lead);
    frac_trajlut tl;
    frac_real out[4];
    int seg, k, counts[5] = {0, 0, 0, 0, 0};
    (void)state;
    p.t0 = FRAC_R(10 * TS); /* table starts at cycle 10 */
    assert_int_equal(frac_trajlut_init(&tl, &p, NULL), FRAC_OK);
    assert_int_equal(frac_trajlut_eval(&tl, 0, out, &seg), FRAC_W_CLAMPED);
    assert_int_equal(seg, FRAC_TRAJLUT_BEFORE);
    assert_close(out[3], ch_tau[0], 0.0); /* rest at the first sample */
    /* cycle 8: the torque, 4 cycles early, is already inside the table */
    frac_trajlut_eval(&tl, 8, out, &seg);
    assert_close(out[3], ch_tau[2], 1e-9);
    assert_int_equal(frac_trajlut_eval(&tl, 5000, out, &seg), FRAC_W_CLAMPED);
    assert_int_equal(seg, FRAC_TRAJLUT_AFTER);
    assert_close(out[0], ch_theta[NS - 1], 0.0);
    assert_close(out[2], ch_dpsi[NS - 1], 0.0);
    frac_trajlut_seek(&tl, 0);
    for (k = 0; k < 260; k++) {
        frac_trajlut_step(&tl, out, &seg);
        counts[seg]++;
    }
    assert_int_equal(counts[FRAC_TRAJLUT_BEFORE], 10);
    assert_int_equal(counts[FRAC_TRAJLUT_PRE], 40);   /* cycles 10..49 */
    assert_int_equal(counts[FRAC_TRAJLUT_MOTION], 101); /* 50..150 */
    assert_int_equal(counts[FRAC_TRAJLUT_POST], 59);  /* 151..209 */
    assert_int_equal(counts[FRAC_TRAJLUT_AFTER], 50);
}

/* A table sampled at 2 Ts, played at Ts, interpolates between samples;
 * a table of the sin^2 trajectory plays back the trajectory itself. */
static void test_trajlut_interpolates_coarser_tables(void **state)
{
    frac_traj tr;
    frac_traj_params tp;
    static frac_real q[401], dq[401], slopes[2 * 401];
    const frac_real *const data[2] = {q, dq};
    frac_trajlut_params p;
    frac_trajlut tl;
    frac_real out[2], d[5];
    int i, k, interp;
    (void)state;
    tp.q_s = FRAC_R(0.0);
    tp.q_e = FRAC_R(1.5707963267948966);
    tp.dq_max = FRAC_R(1.5707963267948966);
    tp.ddq_max = FRAC_R(6.283185307179586);
    tp.t_start = FRAC_R(0.0);
    tp.duration = FRAC_R(0.0);
    assert_int_equal(frac_traj_init(&tr, &tp), FRAC_OK);
    for (i = 0; i < 401; i++) {
        frac_traj_eval(&tr, FRAC_R(i * 2 * 4 * TS), d); /* dt = 8 Ts = 9.6 ms, 3.84 s */
        q[i] = d[0];
        dq[i] = d[1];
    }
    for (interp = FRAC_LUT_LINEAR; interp <= FRAC_LUT_CUBIC; interp++) {
        memset(&p, 0, sizeof p);
        p.channels = 2; p.n = 401; p.data = data; p.t0 = 0; p.dt = FRAC_R(8 * TS); p.Ts = FRAC_R(TS);
        p.lead = NULL; p.t_motion_start = 0; p.t_motion_end = FRAC_R(1.5); p.interp = interp;
        assert_int_equal(frac_trajlut_init(&tl, &p, slopes), FRAC_OK);
        for (k = 0; k < 1600; k++) {
            assert_int_equal(frac_trajlut_step(&tl, out, NULL), FRAC_OK);
            frac_traj_eval(&tr, FRAC_R(k * TS), d);
            assert_close(out[0], d[0], interp == FRAC_LUT_LINEAR ? 1e-4 : 1e-6);
            assert_close(out[1], d[1], interp == FRAC_LUT_LINEAR ? 5e-4 : 5e-5);
        }
    }
}

static void test_trajlut_rejects_bad_parameters(void **state)
{
    const frac_real *const data[4] = {ch_theta, ch_dtheta, ch_dpsi, ch_tau};
    const frac_real *const nulldata[4] = {ch_theta, NULL, ch_dpsi, ch_tau};
    frac_trajlut_params p = make_params(data, NULL), b;
    frac_trajlut tl;
    frac_real out[4];
    (void)state;
    memset(&tl, 0, sizeof tl);
    assert_int_equal(frac_trajlut_step(&tl, out, NULL), FRAC_E_NOT_INIT);
    assert_int_equal(frac_trajlut_seek(&tl, 3), FRAC_E_NOT_INIT);
    b = p; b.channels = 0;
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_DIM);
    b = p; b.channels = FRAC_TRAJLUT_MAX_CH + 1;
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_DIM);
    b = p; b.Ts = FRAC_R(0.0);
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_TS);
    b = p; b.dt = (frac_real)NAN;
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_TS);
    b = p; b.t_motion_end = FRAC_R(0.0);
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_PARAM);
    b = p; b.interp = FRAC_LUT_CUBIC;
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_STORAGE);
    b = p; b.data = nulldata;
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_NULL);
    ch_tau[7] = (frac_real)NAN;
    b = p;
    assert_int_equal(frac_trajlut_init(&tl, &b, NULL), FRAC_E_NONFINITE);
    assert_int_equal(frac_trajlut_init(NULL, &p, NULL), FRAC_E_NULL);
    assert_int_equal(frac_trajlut_eval(NULL, 0, out, NULL), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trajlut_torque_leads_4_and_imu_reference_lags_3),
        cmocka_unit_test(test_trajlut_segments_and_clamped_rest_outside_table),
        cmocka_unit_test(test_trajlut_interpolates_coarser_tables),
        cmocka_unit_test(test_trajlut_rejects_bad_parameters),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
