/* ImuRead (Cyclic #2): scales new frames, drops non-finite ones without
 * advancing the sample counter, ignores repeated frames. */
#include "frac_test.h"
#include "ImuRead.h"

#include <string.h>

static void test_imuread_publishes_new_frames_and_drops_bad_ones(void **state)
{
    static imuread m;
    plc_program prog;
    imuread_inputs in;
    imuread_outputs out;
    (void)state;
    memset(&in, 0, sizeof in);
    imuread_program(&m, &prog, 0.0174532925f, &in, &out); /* deg/s -> rad/s */
    assert_string_equal(prog.name, "ImuRead");
    imuread_init(&m);
    m.in.RawRate = 90.0f;
    imuread_cyclic(&m); /* no new frame yet */
    assert_int_equal(m.out.ImuCounter, 0);
    m.in.FrameCounter = 1;
    imuread_cyclic(&m);
    assert_int_equal(m.out.ImuCounter, 1);
    assert_close(m.out.TipRate, 1.5707963, 1e-6);
    imuread_cyclic(&m); /* same frame again */
    assert_int_equal(m.out.ImuCounter, 1);
    m.in.FrameCounter = 2;
    m.in.RawRate = (REAL)NAN;
    imuread_cyclic(&m);
    assert_int_equal(m.out.ImuCounter, 1);
    assert_int_equal(m.out.Dropped, 1);
    assert_close(m.out.TipRate, 1.5707963, 1e-6);
    m.in.FrameCounter = 3;
    m.in.RawRate = -45.0f;
    imuread_cyclic(&m);
    assert_int_equal(m.out.ImuCounter, 2);
    assert_close(m.out.TipRate, -0.78539816, 1e-6);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_imuread_publishes_new_frames_and_drops_bad_ones),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
