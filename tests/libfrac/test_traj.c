/* sin^2 PTP trajectory, seed 004 Sec. 4.1 with notes 004b section 2 corrections (frac/traj.h). */
#include "frac_test.h"
#include "frac/traj.h"

#define PI 3.14159265358979323846

#if FRAC_REAL_IS_FLOAT
#define TOL 2e-4
#else
#define TOL 1e-9
#endif

/* Table 8.5: q_s = 0, q_e = pi/2, dq_m = pi/2, ddq_m = 2 pi, t_s = 0.5 s, dT = 1.5 s */
static void plan_table_8_5(frac_traj *tr)
{
    frac_traj_params p;
    p.q_s = FRAC_R(0.0);
    p.q_e = FRAC_R(PI / 2.0);
    p.dq_max = FRAC_R(PI / 2.0);
    p.ddq_max = FRAC_R(2.0 * PI);
    p.t_start = FRAC_R(0.5);
    p.duration = FRAC_R(0.0);
    assert_int_equal(frac_traj_init(tr, &p), FRAC_OK);
}

static void test_traj_table_8_5_timing_and_waypoints(void **state)
{
    frac_traj tr;
    frac_real ta, tb, te, d[5];
    (void)state;
    plan_table_8_5(&tr);
    assert_int_equal(frac_traj_times(&tr, &ta, &tb, &te), FRAC_OK);
    assert_close(ta, 0.5, TOL);
    assert_close(te, 1.5, TOL);
    assert_close(tb, 1.0, TOL);
    /* local times 0.5, 1.0, 1.5 are absolute 1.0, 1.5, 2.0 */
    frac_traj_eval(&tr, FRAC_R(1.0), d);
    assert_close(d[0], PI / 8.0, TOL);
    assert_close(d[1], PI / 2.0, TOL);
    frac_traj_eval(&tr, FRAC_R(1.5), d);
    assert_close(d[0], 3.0 * PI / 8.0, TOL);
    frac_traj_eval(&tr, FRAC_R(2.0), d);
    assert_close(d[0], PI / 2.0, TOL);
    assert_close(d[1], 0.0, TOL);
    frac_traj_eval(&tr, FRAC_R(0.75), d);
    assert_close(d[1], PI / 4.0, TOL);
    assert_close(d[2], 2.0 * PI, TOL);
    frac_traj_eval(&tr, FRAC_R(1.75), d);
    assert_close(d[2], -2.0 * PI, TOL);
    frac_traj_eval(&tr, FRAC_R(0.2), d);
    assert_close(d[0], 0.0, 0.0);
    assert_close(d[4], 0.0, 0.0);
    frac_traj_eval(&tr, FRAC_R(7.0), d);
    assert_close(d[0], PI / 2.0, TOL);
    assert_close(d[1], 0.0, 0.0);
}

static void test_traj_continuous_up_to_jerk_with_snap_jump_16_pi_cubed(void **state)
{
    frac_traj tr;
    const double borders[4] = {0.5, 1.0, 1.5, 2.0};
    const double h = 1e-7;
    frac_real lo[5], hi[5];
    int b, i;
    (void)state;
    plan_table_8_5(&tr);
    for (b = 0; b < 4; b++) {
        frac_traj_eval(&tr, FRAC_R(borders[b] - h), lo);
        frac_traj_eval(&tr, FRAC_R(borders[b] + h), hi);
        /* q, dq, ddq, jerk continuous: the jump over 2h is at most |next derivative| * 2h */
        for (i = 0; i < 4; i++) assert_close(hi[i], lo[i], 1e-4 + (FRAC_REAL_IS_FLOAT ? 1e-2 : 0.0));
        /* the 4th derivative jumps by 2 pi^2 ddq_m / t_a^2 = 16 pi^3 */
        assert_close(fabs((double)(hi[4] - lo[4])), 16.0 * PI * PI * PI, 496.1 * 1e-5);
    }
}

static void test_traj_derivatives_are_consistent_and_jerk_max_4_pi_squared(void **state)
{
    frac_traj tr;
    frac_real d0[5], d1[5], dm[5];
    double t, jmax = 0.0, h = 1e-5;
    int i;
    (void)state;
    plan_table_8_5(&tr);
    for (t = 0.5 + 2e-5; t < 2.0 - 2e-5; t += 0.0123) {
        frac_traj_eval(&tr, FRAC_R(t - h), d0);
        frac_traj_eval(&tr, FRAC_R(t + h), d1);
        frac_traj_eval(&tr, FRAC_R(t), dm);
        for (i = 0; i < 4; i++) {
            double fd = ((double)d1[i] - (double)d0[i]) / (2.0 * h);
            assert_close(fd, dm[i + 1], FRAC_REAL_IS_FLOAT ? 5.0 : 1e-4 * (1.0 + fabs((double)dm[i + 1])));
        }
        if (fabs((double)dm[3]) > jmax) jmax = fabs((double)dm[3]);
    }
    frac_traj_eval(&tr, FRAC_R(0.625), dm); /* jerk peak at t_a / 4 */
    assert_close(dm[3], 4.0 * PI * PI, 1e-3);
    assert_true(jmax <= 4.0 * PI * PI + 1e-3);
}

static void test_traj_longer_duration_lowers_velocity_by_4_4(void **state)
{
    frac_traj tr;
    frac_traj_params p;
    frac_real d[5], ta, tb, te;
    (void)state;
    p.q_s = FRAC_R(1.0);
    p.q_e = FRAC_R(1.0 - PI / 2.0); /* negative direction */
    p.dq_max = FRAC_R(PI / 2.0);
    p.ddq_max = FRAC_R(2.0 * PI);
    p.t_start = FRAC_R(0.0);
    p.duration = FRAC_R(3.0);
    assert_int_equal(frac_traj_init(&tr, &p), FRAC_OK);
    frac_traj_times(&tr, &ta, &tb, &te);
    assert_close(te, 3.0, TOL);
    /* (4.4) */
    {
        double a = 2.0 * PI, s = PI / 2.0, v = 0.5 * (a * 3.0 / 2.0 - sqrt(a * a * 9.0 / 4.0 - 2.0 * a * s));
        assert_close(ta, 2.0 * v / a, TOL);
        frac_traj_eval(&tr, FRAC_R(1.5), d);
        assert_close(d[1], -v, TOL);
    }
    frac_traj_eval(&tr, te, d);
    assert_close(d[0], 1.0 - PI / 2.0, TOL);
    frac_traj_eval(&tr, te - FRAC_R(1e-6), d);
    assert_close(d[0], 1.0 - PI / 2.0, 1e-5);
    /* short move: no cruise, still reaches the goal */
    p.q_e = FRAC_R(1.1);
    p.duration = FRAC_R(0.0);
    assert_int_equal(frac_traj_init(&tr, &p), FRAC_OK);
    frac_traj_times(&tr, &ta, &tb, &te);
    assert_close(tb, ta, TOL);
    frac_traj_eval(&tr, te - FRAC_R(1e-7), d);
    assert_close(d[0], 1.1, 1e-5);
}

static void test_traj_rejects_bad_parameters_and_time(void **state)
{
    frac_traj tr;
    frac_traj_params p;
    frac_real d[5] = {7, 7, 7, 7, 7};
    (void)state;
    p.q_s = FRAC_R(0.0);
    p.q_e = FRAC_R(1.0);
    p.dq_max = FRAC_R(1.0);
    p.ddq_max = FRAC_R(0.0);
    p.t_start = FRAC_R(0.0);
    p.duration = FRAC_R(0.0);
    assert_int_equal(frac_traj_init(&tr, &p), FRAC_E_PARAM);
    assert_int_equal(frac_traj_eval(&tr, FRAC_R(0.1), d), FRAC_E_NOT_INIT);
    p.ddq_max = FRAC_R(2.0);
    p.duration = FRAC_R(0.5); /* below t_e_min = 2 */
    assert_int_equal(frac_traj_init(&tr, &p), FRAC_E_PARAM);
    p.duration = FRAC_R(0.0);
    p.q_e = (frac_real)NAN;
    assert_int_equal(frac_traj_init(&tr, &p), FRAC_E_PARAM);
    assert_int_equal(frac_traj_init(NULL, &p), FRAC_E_NULL);
    p.q_e = FRAC_R(1.0);
    assert_int_equal(frac_traj_init(&tr, &p), FRAC_OK);
    assert_int_equal(frac_traj_eval(&tr, (frac_real)NAN, d), FRAC_E_NONFINITE);
    assert_close(d[0], 7.0, 0.0);
    assert_int_equal(frac_traj_eval(&tr, FRAC_R(0.0), NULL), FRAC_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_traj_table_8_5_timing_and_waypoints),
        cmocka_unit_test(test_traj_continuous_up_to_jerk_with_snap_jump_16_pi_cubed),
        cmocka_unit_test(test_traj_derivatives_are_consistent_and_jerk_max_4_pi_squared),
        cmocka_unit_test(test_traj_longer_duration_lowers_velocity_by_4_4),
        cmocka_unit_test(test_traj_rejects_bad_parameters_and_time),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
