/* ParTable block (FracCtrl.fun): a table that fails any check of
 * frac/ptable.h (magic, version, size, CRC, layout, dimensions,
 * finiteness) leaves the block in Error with its StatusID and field. */
#include "frac_test.h"
#include "FracCtrl.h"
#include "ptable_writer.h"

static unsigned char buf[1024];
static const double gains[2] = {320.0, 200.0};
static const double mat[6] = {1, 2, 3, 4, 5, 6};

static unsigned long good_table(void)
{
    ptw_entry e[2];
    e[0].name = "pd"; e[0].rows = 1; e[0].cols = 2; e[0].values = gains;
    e[1].name = "M"; e[1].rows = 2; e[1].cols = 3; e[1].values = mat;
    return ptw_write(buf, sizeof buf, "test", e, 2);
}

static void run(struct ParTable *b, unsigned long size)
{
    memset(b, 0, sizeof *b);
    b->pData = buf;
    b->Size = (UDINT)size;
    b->Enable = 1;
    ParTable(b);
}

static void test_partable_accepts_a_valid_table(void **state)
{
    struct ParTable b;
    frac_real v[6];
    unsigned long size = good_table();
    (void)state;
    run(&b, size);
    assert_true(b.Valid);
    assert_false(b.Error);
    assert_int_equal(b.StatusID, fracSTAT_OK);
    assert_int_equal(b.Entries, 2);
    assert_int_equal(frac_ptable_get(FracPtableObj_C(b.Handle), "M", 2, 3, v), FRAC_OK);
    assert_close(v[5], 6.0, 0.0);
    b.Enable = 0;
    ParTable(&b);
    assert_int_equal(b.StatusID, fracSTAT_DISABLED);
}

static void expect_refused(unsigned long size, UINT status, const char *field)
{
    struct ParTable b;
    run(&b, size);
    assert_true(b.Error);
    assert_false(b.Valid);
    assert_int_equal(b.StatusID, status);
    assert_string_equal(b.FailField, field);
}

static void test_partable_refuses_each_corruption_with_its_status(void **state)
{
    unsigned long size;
    double nan_value;
    (void)state;
    size = good_table();
    buf[0] = 'X';
    expect_refused(size, fracERR_TABLE_MAGIC, "magic");

    size = good_table();
    buf[4] = 2;
    ptw_seal(buf, size);
    expect_refused(size, fracERR_TABLE_VERSION, "version");

    size = good_table();
    buf[size - 20] ^= 0x01; /* one value bit */
    expect_refused(size, fracERR_TABLE_CRC, "crc32");

    size = good_table();
    expect_refused(size - 10, fracERR_TABLE_SIZE, "total_size");

    size = good_table();
    nan_value = NAN;
    memcpy(buf + size - 4 - 8, &nan_value, 8);
    ptw_seal(buf, size);
    {
        struct ParTable b;
        run(&b, size);
        assert_int_equal(b.StatusID, fracERR_NONFINITE);
        assert_int_equal(b.FailEntry, 1);
    }
}

static void test_partable_without_data_reports_null(void **state)
{
    struct ParTable b;
    (void)state;
    memset(&b, 0, sizeof b);
    b.Size = 100;
    b.Enable = 1;
    ParTable(&b);
    assert_true(b.Error);
    assert_int_equal(b.StatusID, fracERR_NULL);
}

static void test_partable_update_keeps_the_valid_table(void **state)
{
    struct ParTable b;
    unsigned long size = good_table();
    (void)state;
    run(&b, size);
    assert_true(b.Valid);
    /* a corrupted download: reported, the validated handle stays */
    buf[size - 20] ^= 0x01;
    b.Update = 1;
    ParTable(&b);
    assert_true(b.Error);
    assert_true(b.Valid);
    assert_int_equal(b.StatusID, fracERR_TABLE_CRC);
    assert_int_equal(b.Entries, 2);
    buf[size - 20] ^= 0x01;
    b.Update = 0;
    ParTable(&b);
    b.Update = 1;
    ParTable(&b);
    assert_false(b.Error);
    assert_int_equal(b.StatusID, fracSTAT_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_partable_accepts_a_valid_table),
        cmocka_unit_test(test_partable_refuses_each_corruption_with_its_status),
        cmocka_unit_test(test_partable_without_data_reports_null),
        cmocka_unit_test(test_partable_update_keeps_the_valid_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
