/* Internal helpers shared by the task runtime's translation units (not installed). */
#ifndef PLC_RT_INTERNAL_H
#define PLC_RT_INTERNAL_H

#include <stddef.h>

/* printf-style message into err[errlen]; does nothing when err is NULL or errlen 0. */
void plc_rt_set_err(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif /* PLC_RT_INTERNAL_H */
