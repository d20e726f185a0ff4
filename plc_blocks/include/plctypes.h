/*
 * plctypes.h - host shim for the IEC 61131-3 elementary data types.
 *
 * On the B&R target these come from Automation Runtime (<bur/plctypes.h>);
 * on the host and on the Cortex-M4F gate this header provides the same
 * names with the same widths, so the generated library header (FracCtrl.h)
 * and the block bodies compile unchanged everywhere.
 *
 * Widths (IEC 61131-3 table 10): BOOL 1 bit stored in a byte (B&R
 * "plcbit"), SINT/USINT 8, INT/UINT 16, DINT/UDINT 32, REAL 32-bit IEEE,
 * LREAL 64-bit IEEE. DINT/UDINT use int: 32 bits on every target this
 * project builds for (x86-64 host, ARMv7-M); C89 has no <stdint.h>, so the
 * widths are checked at compile time below instead.
 */
#ifndef PLCTYPES_H
#define PLCTYPES_H

typedef unsigned char plcbit;
typedef plcbit BOOL;
typedef signed char SINT;
typedef unsigned char USINT;
typedef signed short INT;
typedef unsigned short UINT;
typedef signed int DINT;
typedef unsigned int UDINT;
typedef float REAL;
typedef double LREAL;
typedef char plcstring;

#ifndef TRUE
#define TRUE 1
#endif
#ifndef FALSE
#define FALSE 0
#endif

/* Compile-time width checks: a negative array size fails the build. */
typedef char plctypes_check_int[(sizeof(INT) == 2) ? 1 : -1];
typedef char plctypes_check_dint[(sizeof(DINT) == 4) ? 1 : -1];
typedef char plctypes_check_real[(sizeof(REAL) == 4) ? 1 : -1];
typedef char plctypes_check_lreal[(sizeof(LREAL) == 8) ? 1 : -1];

#endif /* PLCTYPES_H */
