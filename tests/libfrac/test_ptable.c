/* Binary parameter table reader: valid tables, every refusal path with its field. */
#include "frac_test.h"
#include <string.h>
#include "frac/ptable.h"

#define BUF 512

/* Writers for the little-endian layout of frac/ptable.h (independent of the reader). */
static void w16(unsigned char *p, unsigned long v)
{
    p[0] = (unsigned char)(v & 0xFF);
    p[1] = (unsigned char)((v >> 8) & 0xFF);
}

static void w32(unsigned char *p, unsigned long v)
{
    w16(p, v & 0xFFFF);
    w16(p + 2, (v >> 16) & 0xFFFF);
}

/* IEEE-754 double bits of v, little-endian, from the host representation. */
static void wf64(unsigned char *p, double v)
{
    unsigned char b[8];
    double one = 1.0;
    unsigned char ob[8];
    int k, big;
    memcpy(ob, &one, 8);
    big = ob[0] == 0x3F;
    memcpy(b, &v, 8);
    for (k = 0; k < 8; k++) p[k] = big ? b[7 - k] : b[k];
}

static void wf32(unsigned char *p, float v)
{
    unsigned char b[4];
    float one = 1.0f;
    unsigned char ob[4];
    int k, big;
    memcpy(ob, &one, 4);
    big = ob[0] == 0x3F;
    memcpy(b, &v, 4);
    for (k = 0; k < 4; k++) p[k] = big ? b[3 - k] : b[k];
}

static void seal(unsigned char *b, unsigned long total)
{
    w32(b + total - 4, frac_crc32(b, total - 4));
}

/* Table "arm": K (1 x 3) = {1.5, -2.25, 1e-3}, Ts (1 x 1) = 1.2e-3; float64.
 * Directory 48..112, K at 112 (24 bytes), Ts at 136, CRC at 144; total 148. */
static unsigned long make_f64(unsigned char *b)
{
    memset(b, 0, BUF);
    memcpy(b, "FRPT", 4);
    w16(b + 4, 1);
    w16(b + 6, FRAC_PTABLE_F64);
    w32(b + 8, 148);
    w32(b + 12, 2);
    memcpy(b + 16, "arm", 3);
    memcpy(b + 48, "K", 1);
    w16(b + 48 + 24, 1);
    w16(b + 48 + 26, 3);
    w32(b + 48 + 28, 112);
    memcpy(b + 80, "Ts", 2);
    w16(b + 80 + 24, 1);
    w16(b + 80 + 26, 1);
    w32(b + 80 + 28, 136);
    wf64(b + 112, 1.5);
    wf64(b + 120, -2.25);
    wf64(b + 128, 1e-3);
    wf64(b + 136, 1.2e-3);
    seal(b, 148);
    return 148;
}

/* Same content in float32: K at 112 (12 bytes), Ts at 128, CRC at 132; total 136. */
static unsigned long make_f32(unsigned char *b)
{
    make_f64(b);
    w16(b + 6, FRAC_PTABLE_F32);
    w32(b + 8, 136);
    w32(b + 80 + 28, 128);
    memset(b + 112, 0, 40);
    wf32(b + 112, 1.5f);
    wf32(b + 116, -2.25f);
    wf32(b + 120, 1e-3f);
    wf32(b + 128, 1.2e-3f);
    seal(b, 136);
    return 136;
}

static void test_crc32_matches_the_ieee_check_value(void **state)
{
    (void)state;
    assert_true(frac_crc32((const unsigned char *)"123456789", 9) == 0xCBF43926UL);
    assert_true(frac_crc32((const unsigned char *)"", 0) == 0UL);
}

static void test_valid_float64_table_reads_back_exact_values(void **state)
{
    unsigned char b[BUF];
    frac_ptable t;
    frac_ptable_entry e;
    frac_real k[3], ts;
    char name[FRAC_PTABLE_TABLE_NAME_LEN];
    unsigned long n = make_f64(b);
    (void)state;
    assert_int_equal(frac_ptable_open(&t, b, n), FRAC_OK);
    assert_int_equal(t.n_entries, 2);
    assert_int_equal(frac_ptable_name(&t, name), FRAC_OK);
    assert_string_equal(name, "arm");
    assert_int_equal(frac_ptable_find(&t, "K", &e), FRAC_OK);
    assert_int_equal(e.rows, 1);
    assert_int_equal(e.cols, 3);
    assert_int_equal(frac_ptable_get(&t, "K", 1, 3, k), FRAC_OK);
    assert_true(k[0] == FRAC_R(1.5) && k[1] == FRAC_R(-2.25) && k[2] == (frac_real)1e-3);
    assert_int_equal(frac_ptable_get(&t, "Ts", 1, 1, &ts), FRAC_OK);
    assert_true(ts == (frac_real)1.2e-3);
    /* a buffer larger than the table (padded data object) is accepted */
    assert_int_equal(frac_ptable_open(&t, b, BUF), FRAC_OK);
}

static void test_valid_float32_table_reads_back_exact_values(void **state)
{
    unsigned char b[BUF];
    frac_ptable t;
    frac_real k[3];
    unsigned long n = make_f32(b);
    (void)state;
    assert_int_equal(frac_ptable_open(&t, b, n), FRAC_OK);
    assert_int_equal(t.elem_type, FRAC_PTABLE_F32);
    assert_int_equal(frac_ptable_get(&t, "K", 1, 3, k), FRAC_OK);
    assert_true(k[2] == (frac_real)1e-3f);
}

static void expect_refusal(unsigned char *b, unsigned long n, frac_status want, const char *field, long entry)
{
    frac_ptable t;
    assert_int_equal(frac_ptable_open(&t, b, n), want);
    assert_false(t.valid);
    assert_string_equal(t.fail_field, field);
    assert_int_equal(t.fail_entry, entry);
}

static void test_header_failures_are_refused_naming_the_field(void **state)
{
    unsigned char b[BUF];
    unsigned long n;
    (void)state;
    n = make_f64(b);
    expect_refusal(b, 40, FRAC_E_SIZE, "size", -1);
    expect_refusal(b, n - 1, FRAC_E_SIZE, "total_size", -1); /* truncated */
    b[0] = 'X';
    expect_refusal(b, n, FRAC_E_MAGIC, "magic", -1);
    n = make_f64(b);
    w16(b + 4, 2);
    expect_refusal(b, n, FRAC_E_VERSION, "version", -1);
    n = make_f64(b);
    b[120] ^= 0x01; /* one flipped bit in a value */
    expect_refusal(b, n, FRAC_E_CRC, "crc32", -1);
    n = make_f64(b);
    w32(b + 12, 1000);
    seal(b, n);
    expect_refusal(b, n, FRAC_E_SIZE, "n_entries", -1);
    n = make_f64(b);
    w16(b + 6, 3);
    seal(b, n);
    expect_refusal(b, n, FRAC_E_FORMAT, "elem_type", -1);
    n = make_f64(b);
    b[16] = '9';
    seal(b, n);
    expect_refusal(b, n, FRAC_E_FORMAT, "table_name", -1);
}

static void test_entry_failures_are_refused_naming_the_entry(void **state)
{
    unsigned char b[BUF];
    unsigned long n;
    volatile double zero = 0.0;
    (void)state;
    n = make_f64(b);
    memcpy(b + 80, "K", 2); /* duplicate name */
    seal(b, n);
    expect_refusal(b, n, FRAC_E_FORMAT, "entry.name", 1);
    n = make_f64(b);
    b[81] = '-';
    seal(b, n);
    expect_refusal(b, n, FRAC_E_FORMAT, "entry.name", 1);
    n = make_f64(b);
    w16(b + 48 + 24, 0);
    seal(b, n);
    expect_refusal(b, n, FRAC_E_DIM, "entry.rows", 0);
    n = make_f64(b);
    w16(b + 80 + 26, 0);
    seal(b, n);
    expect_refusal(b, n, FRAC_E_DIM, "entry.cols", 1);
    n = make_f64(b);
    w16(b + 48 + 26, 5); /* K would overrun into the CRC */
    seal(b, n);
    expect_refusal(b, n, FRAC_E_DIM, "entry.offset", 0);
    n = make_f64(b);
    w32(b + 80 + 28, 132);
    seal(b, n);
    expect_refusal(b, n, FRAC_E_FORMAT, "entry.offset", 1);
    n = make_f64(b);
    w32(b + 80 + 28, 48); /* points into the directory */
    seal(b, n);
    expect_refusal(b, n, FRAC_E_DIM, "entry.offset", 1);
    n = make_f64(b);
    wf64(b + 128, zero / zero);
    seal(b, n);
    expect_refusal(b, n, FRAC_E_NONFINITE, "entry.values", 0);
    n = make_f64(b);
    wf64(b + 136, 1.0 / zero);
    seal(b, n);
    expect_refusal(b, n, FRAC_E_NONFINITE, "entry.values", 1);
#if FRAC_REAL_IS_FLOAT
    n = make_f64(b);
    wf64(b + 136, 1e300); /* finite in float64, not representable as frac_real */
    seal(b, n);
    expect_refusal(b, n, FRAC_E_NONFINITE, "entry.values", 1);
#endif
}

static void test_lookups_check_name_dimensions_and_state(void **state)
{
    unsigned char b[BUF];
    frac_ptable t;
    frac_ptable_entry e;
    frac_real k[4] = {FRAC_R(7.0), FRAC_R(7.0), FRAC_R(7.0), FRAC_R(7.0)};
    unsigned long n = make_f64(b);
    (void)state;
    assert_int_equal(frac_ptable_open(NULL, b, n), FRAC_E_NULL);
    assert_int_equal(frac_ptable_open(&t, NULL, n), FRAC_E_NULL);
    assert_string_equal(t.fail_field, "data");
    assert_int_equal(frac_ptable_get(&t, "K", 1, 3, k), FRAC_E_NOT_INIT);
    assert_int_equal(frac_ptable_open(&t, b, n), FRAC_OK);
    assert_int_equal(frac_ptable_get(&t, "K", 3, 1, k), FRAC_E_DIM);
    assert_true(k[0] == FRAC_R(7.0)); /* untouched on refusal */
    assert_int_equal(frac_ptable_get(&t, "L", 1, 1, k), FRAC_E_NOT_FOUND);
    assert_int_equal(frac_ptable_get(&t, "", 1, 1, k), FRAC_E_NOT_FOUND);
    assert_int_equal(frac_ptable_get(&t, "K", 1, 3, NULL), FRAC_E_NULL);
    assert_int_equal(frac_ptable_find(&t, NULL, &e), FRAC_E_NULL);
    assert_int_equal(frac_ptable_entry_at(&t, 2, &e), FRAC_E_DIM);
    assert_int_equal(frac_ptable_entry_at(&t, 1, &e), FRAC_OK);
    assert_string_equal(e.name, "Ts");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc32_matches_the_ieee_check_value),
        cmocka_unit_test(test_valid_float64_table_reads_back_exact_values),
        cmocka_unit_test(test_valid_float32_table_reads_back_exact_values),
        cmocka_unit_test(test_header_failures_are_refused_naming_the_field),
        cmocka_unit_test(test_entry_failures_are_refused_naming_the_entry),
        cmocka_unit_test(test_lookups_check_name_dimensions_and_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
