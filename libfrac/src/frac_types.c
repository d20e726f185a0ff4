/* frac_types.c - status strings and version of libfrac. */
#include "frac/frac_types.h"

const char *frac_status_str(int status)
{
    switch (status) {
    case FRAC_OK: return "ok";
    case FRAC_W_CLAMPED: return "warning: clamped to limits";
    case FRAC_W_EXTRAPOLATED: return "warning: extrapolated outside the table";
    case FRAC_W_MEAS_SKIPPED: return "warning: non-finite measurement skipped";
    case FRAC_W_COV_RESET: return "warning: covariance reset";
    case FRAC_W_SATURATED: return "warning: output saturated";
    case FRAC_E_NULL: return "error: null pointer";
    case FRAC_E_NONFINITE: return "error: non-finite input";
    case FRAC_E_NOT_INIT: return "error: not initialised";
    case FRAC_E_STORAGE: return "error: storage too small";
    case FRAC_E_DIM: return "error: invalid dimension";
    case FRAC_E_ORDER: return "error: fractional order out of range";
    case FRAC_E_BAND: return "error: invalid frequency band";
    case FRAC_E_TS: return "error: invalid sampling time";
    case FRAC_E_GAIN: return "error: invalid gain or time constant";
    case FRAC_E_LIMITS: return "error: invalid output limits";
    case FRAC_E_PARAM: return "error: invalid parameter";
    case FRAC_E_NOT_MONOTONE: return "error: not strictly monotone";
    case FRAC_E_NOT_POSDEF: return "error: matrix not positive definite";
    case FRAC_E_UNSTABLE: return "error: unstable realization";
    case FRAC_E_NUMERIC: return "error: numerical failure";
    case FRAC_E_MAGIC: return "error: table magic number wrong";
    case FRAC_E_VERSION: return "error: table format version unsupported";
    case FRAC_E_CRC: return "error: table CRC32 mismatch";
    case FRAC_E_SIZE: return "error: table truncated or size inconsistent";
    case FRAC_E_FORMAT: return "error: table layout invalid";
    case FRAC_E_NOT_FOUND: return "error: table entry not found";
    default: return "unknown status";
    }
}

const char *frac_version(void)
{
    return "0.1.0";
}
