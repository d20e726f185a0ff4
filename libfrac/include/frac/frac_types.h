/*
 * frac_types.h - the real type, status codes and portable math of libfrac.
 *
 * One real type, frac_real: double by default, float when the library and
 * every user are compiled with -DFRAC_REAL_FLOAT=1 (the single compile-time
 * switch). All public functions take and return frac_real.
 *
 * Status convention (ARCHITECTURE.md, libfrac rules): FRAC_OK (0) is
 * success, negative values are errors, positive values are warnings that
 * still produced a valid output (e.g. a lookup that was clamped). A step
 * that returns an error leaves the object's state untouched and its output
 * at the last finite value, so the object stays usable.
 *
 * C89: no // comments, no mixed declarations, no inline, no long long.
 */
#ifndef FRAC_TYPES_H
#define FRAC_TYPES_H

#include <math.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(FRAC_REAL_FLOAT) && FRAC_REAL_FLOAT
typedef float frac_real;
#define FRAC_REAL_IS_FLOAT 1
#define FRAC_REAL_EPSILON 1.1920929e-07f
#define FRAC_REAL_MAX 3.40282347e+38f
#else
typedef double frac_real;
#define FRAC_REAL_IS_FLOAT 0
#define FRAC_REAL_EPSILON 2.2204460492503131e-16
#define FRAC_REAL_MAX 1.7976931348623157e+308
#endif

/* Literal of type frac_real: FRAC_R(0.5). */
#define FRAC_R(x) ((frac_real)(x))

/*
 * Math: C89 libm has only the double functions; with float and a C99
 * compiler the f-suffixed ones are used so that a Cortex-M4F stays in
 * single precision.
 */
#if FRAC_REAL_IS_FLOAT && defined(__STDC_VERSION__) && (__STDC_VERSION__ >= 199901L)
#define FRAC_SQRT(x) sqrtf(x)
#define FRAC_FABS(x) fabsf(x)
#define FRAC_EXP(x) expf(x)
#define FRAC_LOG(x) logf(x)
#define FRAC_POW(x, y) powf((x), (y))
#define FRAC_SIN(x) sinf(x)
#define FRAC_COS(x) cosf(x)
#define FRAC_TAN(x) tanf(x)
#define FRAC_ATAN(x) atanf(x)
#define FRAC_ATAN2(y, x) atan2f((y), (x))
#define FRAC_TANH(x) tanhf(x)
#define FRAC_FLOOR(x) floorf(x)
#else
#define FRAC_SQRT(x) ((frac_real)sqrt((double)(x)))
#define FRAC_FABS(x) ((frac_real)fabs((double)(x)))
#define FRAC_EXP(x) ((frac_real)exp((double)(x)))
#define FRAC_LOG(x) ((frac_real)log((double)(x)))
#define FRAC_POW(x, y) ((frac_real)pow((double)(x), (double)(y)))
#define FRAC_SIN(x) ((frac_real)sin((double)(x)))
#define FRAC_COS(x) ((frac_real)cos((double)(x)))
#define FRAC_TAN(x) ((frac_real)tan((double)(x)))
#define FRAC_ATAN(x) ((frac_real)atan((double)(x)))
#define FRAC_ATAN2(y, x) ((frac_real)atan2((double)(y), (double)(x)))
#define FRAC_TANH(x) ((frac_real)tanh((double)(x)))
#define FRAC_FLOOR(x) ((frac_real)floor((double)(x)))
#endif

#define FRAC_PI FRAC_R(3.14159265358979323846)

/*
 * Finite test without C99 isfinite(): NaN fails x == x, +-Inf fails
 * x - x == 0. Valid as long as the build does not use -ffast-math
 * (the build never does; the gates compile with strict flags).
 */
#define FRAC_ISFINITE(x) (((x) == (x)) && (((x) - (x)) == FRAC_R(0.0)))

/* Status codes shared by every libfrac object. */
typedef enum frac_status {
    FRAC_OK = 0,
    /* warnings: output valid */
    FRAC_W_CLAMPED = 1,        /* output or lookup clamped to its limits */
    FRAC_W_EXTRAPOLATED = 2,   /* lookup outside the table, extrapolated */
    FRAC_W_MEAS_SKIPPED = 3,   /* non-finite measurement skipped, prediction only */
    FRAC_W_COV_RESET = 4,      /* covariance lost definiteness and was reset */
    FRAC_W_SATURATED = 5,      /* actuator limit active, anti-windup engaged */
    /* errors: state untouched, output holds its last finite value */
    FRAC_E_NULL = -1,          /* a required pointer is NULL */
    FRAC_E_NONFINITE = -2,     /* NaN or Inf at an input */
    FRAC_E_NOT_INIT = -3,      /* object used before a successful init */
    FRAC_E_STORAGE = -4,       /* caller storage too small or missing */
    FRAC_E_DIM = -5,           /* dimension zero or above the compile-time capacity */
    FRAC_E_ORDER = -6,         /* fractional order out of range */
    FRAC_E_BAND = -7,          /* frequency band invalid (wb <= 0, wh <= wb, above Nyquist) */
    FRAC_E_TS = -8,            /* sampling time not finite and positive */
    FRAC_E_GAIN = -9,          /* gain or time constant invalid */
    FRAC_E_LIMITS = -10,       /* output limits inverted or non-finite */
    FRAC_E_PARAM = -11,        /* other parameter invalid (non-finite or out of range) */
    FRAC_E_NOT_MONOTONE = -12, /* breakpoints not strictly increasing / data not monotone */
    FRAC_E_NOT_POSDEF = -13,   /* matrix not positive definite */
    FRAC_E_UNSTABLE = -14,     /* realization unstable (a pole outside the unit circle) */
    FRAC_E_NUMERIC = -15,      /* numerical failure (singular system, overflow) */
    FRAC_E_MAGIC = -16,        /* parameter table: wrong magic number */
    FRAC_E_VERSION = -17,      /* parameter table: unsupported format version */
    FRAC_E_CRC = -18,          /* parameter table: CRC32 mismatch */
    FRAC_E_SIZE = -19,         /* parameter table: truncated or total size inconsistent */
    FRAC_E_FORMAT = -20,       /* parameter table: layout invalid (element type, names, offsets) */
    FRAC_E_NOT_FOUND = -21     /* parameter table: no entry of that name */
} frac_status;

/* Human-readable name of a status code; never NULL. */
const char *frac_status_str(int status);

/* Library version "MAJOR.MINOR.PATCH". */
const char *frac_version(void);

#ifdef __cplusplus
}
#endif

#endif /* FRAC_TYPES_H */
