/* Small dense linear algebra (frac/mat.h). */
#include "frac_test.h"
#include "frac/mat.h"

static const frac_real A23[6] = {1, 2, 3, 4, 5, 6};          /* 2 x 3 */
static const frac_real B32[6] = {7, 8, 9, 10, 11, 12};       /* 3 x 2 */
/* symmetric positive definite 3 x 3 */
static const frac_real S3[9] = {4, 2, 0.4, 2, 5, 1, 0.4, 1, 3};

static void test_mat_products_match_hand_computed_values(void **state)
{
    frac_real y[2], x[3] = {1, -1, 2}, C[4], Ct[4], yy[2] = {10, 20};
    (void)state;
    assert_int_equal(frac_mat_vec(A23, 2, 3, x, y), FRAC_OK);
    assert_close(y[0], 1 - 2 + 6, 0.0);
    assert_close(y[1], 4 - 5 + 12, 0.0);
    assert_int_equal(frac_mat_vec_add(A23, 2, 3, x, yy), FRAC_OK);
    assert_close(yy[0], 15, 0.0);
    assert_close(yy[1], 31, 0.0);
    assert_int_equal(frac_mat_mul(A23, 2, 3, B32, 2, C), FRAC_OK);
    assert_close(C[0], 58, 0.0);
    assert_close(C[1], 64, 0.0);
    assert_close(C[2], 139, 0.0);
    assert_close(C[3], 154, 0.0);
    /* A A^T */
    assert_int_equal(frac_mat_mul_bt(A23, 2, 3, A23, 2, Ct), FRAC_OK);
    assert_close(Ct[0], 14, 0.0);
    assert_close(Ct[1], 32, 0.0);
    assert_close(Ct[2], 32, 0.0);
    assert_close(Ct[3], 77, 0.0);
}

/* every row/column remainder of the blocked kernel against a plain loop */
static void test_mat_vec_matches_plain_loop_for_all_shapes(void **state)
{
    frac_real M[11 * 11], x[11], y[11], ya[11];
    size_t r, c, i, j;
    (void)state;
    for (i = 0; i < 11 * 11; i++) M[i] = (frac_real)(0.37 * (double)i - 0.011 * (double)(i * i % 17));
    for (j = 0; j < 11; j++) x[j] = (frac_real)(1.0 - 0.3 * (double)j);
    for (r = 1; r <= 11; r++) {
        for (c = 1; c <= 11; c++) {
            for (i = 0; i < r; i++) ya[i] = (frac_real)i;
            assert_int_equal(frac_mat_vec(M, r, c, x, y), FRAC_OK);
            assert_int_equal(frac_mat_vec_add(M, r, c, x, ya), FRAC_OK);
            for (i = 0; i < r; i++) {
                double s = 0.0;
                for (j = 0; j < c; j++) s += (double)M[i * c + j] * (double)x[j];
                assert_close(y[i], s, 1e-9 * (1.0 + fabs(s)));
                assert_close(ya[i], s + (double)i, 1e-9 * (1.0 + fabs(s) + (double)i));
            }
        }
    }
}

static void test_mat_congruence_equals_product_and_is_exactly_symmetric(void **state)
{
    frac_real work[6], P[4], AP[6], APA[4];
    const frac_real Q[4] = {1, 0.5, 0.5, 2};
    size_t i;
    (void)state;
    assert_int_equal(frac_mat_sym_congruence(A23, 2, 3, S3, Q, work, P), FRAC_OK);
    frac_mat_mul(A23, 2, 3, S3, 3, AP);
    frac_mat_mul_bt(AP, 2, 3, A23, 2, APA);
    for (i = 0; i < 4; i++) assert_close(P[i], APA[i] + Q[i], 1e-12 * fabs(APA[i]) + 1e-5);
    assert_true(P[1] == P[2]);
    assert_int_equal(frac_mat_sym_congruence(A23, 2, 3, S3, NULL, work, P), FRAC_OK);
    assert_close(P[3], APA[3], 1e-9 * APA[3] + 1e-4);
}

static void test_mat_cholesky_solves_spd_system(void **state)
{
    frac_real L[9], b[3] = {1, 2, 3}, x[3], r[3];
    size_t i;
    (void)state;
    for (i = 0; i < 9; i++) L[i] = S3[i];
    assert_int_equal(frac_mat_cholesky(L, 3), FRAC_OK);
    assert_close(L[0], 2.0, 1e-6);
    assert_close(L[1], 0.0, 0.0);
    assert_int_equal(frac_mat_cholesky_solve(L, 3, b, x), FRAC_OK);
    frac_mat_vec(S3, 3, 3, x, r);
    for (i = 0; i < 3; i++) assert_close(r[i], b[i], 1e-5);
    /* in place */
    assert_int_equal(frac_mat_cholesky_solve(L, 3, b, b), FRAC_OK);
    for (i = 0; i < 3; i++) assert_close(b[i], x[i], 0.0);
}

static void test_mat_cholesky_rejects_indefinite_and_nan(void **state)
{
    frac_real M[4] = {1, 2, 2, 1};
    frac_real N[4] = {1, 0, 0, 0};
    (void)state;
    assert_int_equal(frac_mat_cholesky(M, 2), FRAC_E_NOT_POSDEF);
    N[3] = (frac_real)NAN;
    assert_int_equal(frac_mat_cholesky(N, 2), FRAC_E_NOT_POSDEF);
}

static void test_mat_ldl_solves_indefinite_symmetric_system(void **state)
{
    frac_real M[9] = {2, 1, 0, 1, -3, 1, 0, 1, 4};
    frac_real LD[9], b[3] = {1, -2, 0.5}, x[3], r[3];
    frac_real Z[4] = {0, 1, 1, 0};
    size_t i;
    (void)state;
    for (i = 0; i < 9; i++) LD[i] = M[i];
    assert_int_equal(frac_mat_ldl(LD, 3), FRAC_OK);
    assert_true(LD[4] < 0.0); /* D holds the negative pivot */
    assert_int_equal(frac_mat_ldl_solve(LD, 3, b, x), FRAC_OK);
    frac_mat_vec(M, 3, 3, x, r);
    for (i = 0; i < 3; i++) assert_close(r[i], b[i], 1e-5);
    assert_int_equal(frac_mat_ldl(Z, 2), FRAC_E_NUMERIC);
}

static void test_mat_rejects_null_and_bad_dimensions(void **state)
{
    frac_real y[2], x[3] = {0, 0, 0}, big[1];
    (void)state;
    assert_int_equal(frac_mat_vec(NULL, 2, 3, x, y), FRAC_E_NULL);
    assert_int_equal(frac_mat_vec(A23, 0, 3, x, y), FRAC_E_DIM);
    assert_int_equal(frac_mat_vec_add(A23, 2, FRAC_MAT_MAX + 1, x, y), FRAC_E_DIM);
    assert_int_equal(frac_mat_mul(A23, 2, 3, NULL, 2, y), FRAC_E_NULL);
    assert_int_equal(frac_mat_mul_bt(A23, 2, 0, A23, 2, y), FRAC_E_DIM);
    assert_int_equal(frac_mat_cholesky(big, 0), FRAC_E_DIM);
    assert_int_equal(frac_mat_cholesky(NULL, 2), FRAC_E_NULL);
    assert_int_equal(frac_mat_ldl(big, FRAC_MAT_MAX + 1), FRAC_E_DIM);
    assert_int_equal(frac_mat_symmetrize(NULL, 2), FRAC_E_NULL);
    assert_int_equal(frac_mat_sym_congruence(A23, 2, 3, S3, NULL, NULL, y), FRAC_E_NULL);
    assert_int_equal(frac_mat_all_finite(NULL, 1), 0);
    x[1] = (frac_real)INFINITY;
    assert_int_equal(frac_mat_all_finite(x, 3), 0);
    assert_int_equal(frac_mat_all_finite(x, 1), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mat_products_match_hand_computed_values),
        cmocka_unit_test(test_mat_vec_matches_plain_loop_for_all_shapes),
        cmocka_unit_test(test_mat_congruence_equals_product_and_is_exactly_symmetric),
        cmocka_unit_test(test_mat_cholesky_solves_spd_system),
        cmocka_unit_test(test_mat_cholesky_rejects_indefinite_and_nan),
        cmocka_unit_test(test_mat_ldl_solves_indefinite_symmetric_system),
        cmocka_unit_test(test_mat_rejects_null_and_bad_dimensions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
