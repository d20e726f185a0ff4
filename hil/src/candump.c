/* candump log format writer and reader; format in hil/candump.h. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "hil/candump.h"

/* The interface field of the grammar (hil/candump.h): 1..15 graphic ASCII
 * bytes (0x21..0x7E), none of them '(', ')' or '#'. Shared by writer and
 * reader. */
static int iface_ok(const char *s, size_t len)
{
    size_t i;
    if (len == 0 || len >= HIL_CANDUMP_IFACE_MAX)
        return 0;
    for (i = 0; i < len; i++)
        if (s[i] < 0x21 || s[i] > 0x7E || s[i] == '(' || s[i] == ')' || s[i] == '#')
            return 0;
    return 1;
}

/* Writes v as exactly `digits` decimal digits (zero padded) ending before
 * end; returns the start. v < 10^digits is the caller's guarantee. */
static char *put_dec(char *end, unsigned long long v, int digits)
{
    while (digits-- > 0) {
        *--end = (char)('0' + v % 10u);
        v /= 10u;
    }
    return end;
}

/* Formatted by hand, not by snprintf: the log line is the hot path of a
 * lockstep run (one per frame), and printf's format interpreter cost most
 * of the bench's time. */
int hil_candump_format(char *buf, size_t n, double t, const char *iface,
                       const struct hil_can_frame *f)
{
    static const char hex[] = "0123456789ABCDEF";
    long long sec, usec;
    int st, i, idd;
    size_t il, len, need;
    char *p;
    uint32_t id;
    if (!buf || !iface || !f || !(t >= 0.0) || t > HIL_CANDUMP_T_MAX)
        return HIL_E_ARG;
    il = strlen(iface);
    if (!iface_ok(iface, il))
        return HIL_E_ARG;
    st = hil_can_frame_check(f);
    if (st != HIL_OK)
        return st;
    /* t - floor(t) is exact in binary floating point, t * 1e6 is not for
     * epoch times; rounding the fraction alone keeps the microsecond right.
     * A fraction rounding up to 1 s carries into the seconds. */
    sec = (long long)floor(t);
    usec = (long long)floor((t - (double)sec) * 1e6 + 0.5);
    if (usec >= 1000000) {
        sec++;
        usec -= 1000000;
    }
    /* the reader's bound, on the value as the line will carry it */
    if ((double)sec + (double)usec * 1e-6 > HIL_CANDUMP_T_MAX)
        return HIL_E_ARG;
    {
        /* seconds: at least 10 digits (candump's %010ld), more if needed */
        int sd = 10;
        unsigned long long v = (unsigned long long)sec;
        while (sd < 20 && v >= 10000000000ull) {
            v /= 10u;
            sd++;
        }
        idd = (f->id & HIL_CAN_EFF_FLAG) ? 8 : 3;
        need = 1 + (size_t)sd + 1 + 6 + 2 + il + 1 + (size_t)idd + 1 + 2u * f->dlc + 1 + 1;
        if (need > n)
            return HIL_E_FULL;
        p = buf;
        *p++ = '(';
        put_dec(p + sd, (unsigned long long)sec, sd);
        p += sd;
        *p++ = '.';
        put_dec(p + 6, (unsigned long long)usec, 6);
        p += 6;
        *p++ = ')';
        *p++ = ' ';
        memcpy(p, iface, il);
        p += il;
        *p++ = ' ';
    }
    id = f->id & (idd == 8 ? HIL_CAN_EFF_MASK : HIL_CAN_SFF_MASK);
    for (i = idd - 1; i >= 0; i--) {
        p[i] = hex[id & 0xFu];
        id >>= 4;
    }
    p += idd;
    *p++ = '#';
    for (i = 0; i < f->dlc; i++) {
        *p++ = hex[f->data[i] >> 4];
        *p++ = hex[f->data[i] & 0xFu];
    }
    *p++ = '\n';
    *p = '\0';
    len = (size_t)(p - buf);
    return (int)len;
}

static int hexval(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

int hil_candump_parse(const char *line, double *t, char *iface, struct hil_can_frame *f)
{
    const char *p, *q;
    double sec = 0.0, usec = 0.0;
    uint32_t id = 0;
    int ndig = 0, nbytes = 0;
    size_t il;
    if (!line || !t || !iface || !f)
        return HIL_E_ARG;
    p = line;
    if (*p++ != '(')
        return HIL_E_FORMAT;
    while (*p >= '0' && *p <= '9' && ndig < 17) {
        sec = sec * 10.0 + (*p++ - '0');
        ndig++;
    }
    if (ndig == 0 || ndig > 16 || *p++ != '.')
        return HIL_E_FORMAT;
    for (ndig = 0; ndig < 6; ndig++, p++) {
        if (*p < '0' || *p > '9')
            return HIL_E_FORMAT;
        usec = usec * 10.0 + (*p - '0');
    }
    if (*p++ != ')' || *p++ != ' ' || sec + usec * 1e-6 > HIL_CANDUMP_T_MAX)
        return HIL_E_FORMAT;
    q = strchr(p, ' ');
    if (!q)
        return HIL_E_FORMAT;
    il = (size_t)(q - p);
    if (!iface_ok(p, il))
        return HIL_E_FORMAT;
    memcpy(iface, p, il);
    iface[il] = '\0';
    p = q + 1;
    ndig = 0;
    while (hexval(*p) >= 0 && ndig < 9) {
        id = (id << 4) | (uint32_t)hexval(*p++);
        ndig++;
    }
    if (*p++ != '#')
        return HIL_E_FORMAT;
    memset(f, 0, sizeof *f);
    if (ndig == 3 && id <= HIL_CAN_SFF_MASK)
        f->id = id;
    else if (ndig == 8 && id <= HIL_CAN_EFF_MASK)
        f->id = id | HIL_CAN_EFF_FLAG;
    else
        return HIL_E_FORMAT;
    while (hexval(p[0]) >= 0) {
        if (hexval(p[1]) < 0)
            return HIL_E_FORMAT;
        if (nbytes == HIL_CAN_MAX_DLC)
            return HIL_E_DLC;
        f->data[nbytes++] = (uint8_t)(hexval(p[0]) * 16 + hexval(p[1]));
        p += 2;
    }
    if (*p == '\r')
        p++;
    if (*p == '\n')
        p++;
    if (*p != '\0')
        return HIL_E_FORMAT;
    f->dlc = (uint8_t)nbytes;
    *t = sec + usec * 1e-6;
    return HIL_OK;
}
