/* Shared includes and helpers for the CMocka tests. */
#ifndef FRAC_TEST_H
#define FRAC_TEST_H
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>

/* Asserts |got - want| <= tol, printing both values on failure. */
#define assert_close(got, want, tol) do { \
    double g_ = (double)(got), w_ = (double)(want), t_ = (double)(tol); \
    if (!(fabs(g_ - w_) <= t_)) fail_msg("%s = %.12g, expected %.12g +- %.3g", #got, g_, w_, t_); \
} while (0)

/* Asserts |got - want| <= rtol * |want|. */
#define assert_rel(got, want, rtol) do { \
    double g_ = (double)(got), w_ = (double)(want), t_ = (double)(rtol) * fabs((double)(want)); \
    if (!(fabs(g_ - w_) <= t_)) fail_msg("%s = %.12g, expected %.12g (rel tol %.3g)", #got, g_, w_, (double)(rtol)); \
} while (0)
#endif
