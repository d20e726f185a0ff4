/* candump log format writer and reader; format in hil/candump.h. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "hil/candump.h"

int hil_candump_format(char *buf, size_t n, double t, const char *iface,
                       const struct hil_can_frame *f)
{
    long long sec, usec;
    int st, len, i;
    size_t il;
    if (!buf || !iface || !f || !(t >= 0.0) || t > 9.0e15)
        return HIL_E_ARG;
    il = strlen(iface);
    if (il == 0 || il >= HIL_CANDUMP_IFACE_MAX || strpbrk(iface, " \t\r\n()#"))
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
    if (f->id & HIL_CAN_EFF_FLAG)
        len = snprintf(buf, n, "(%010lld.%06lld) %s %08X#", sec, usec, iface,
                       (unsigned)(f->id & HIL_CAN_EFF_MASK));
    else
        len = snprintf(buf, n, "(%010lld.%06lld) %s %03X#", sec, usec, iface, (unsigned)f->id);
    if (len < 0 || (size_t)len + 2u * f->dlc + 2u > n)
        return HIL_E_FULL;
    for (i = 0; i < f->dlc; i++)
        len += snprintf(buf + len, n - (size_t)len, "%02X", f->data[i]);
    buf[len++] = '\n';
    buf[len] = '\0';
    return len;
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
    double sec = 0.0, frac = 0.0, scale = 0.1;
    uint32_t id = 0;
    int ndig = 0, nbytes = 0;
    size_t il;
    if (!line || !t || !iface || !f)
        return HIL_E_ARG;
    p = line;
    if (*p++ != '(')
        return HIL_E_FORMAT;
    if (*p < '0' || *p > '9')
        return HIL_E_FORMAT;
    while (*p >= '0' && *p <= '9' && ndig < 16) {
        sec = sec * 10.0 + (*p++ - '0');
        ndig++;
    }
    if (*p++ != '.')
        return HIL_E_FORMAT;
    ndig = 0;
    while (*p >= '0' && *p <= '9' && ndig < 9) {
        frac += scale * (*p++ - '0');
        scale *= 0.1;
        ndig++;
    }
    if (ndig == 0 || *p++ != ')' || *p++ != ' ')
        return HIL_E_FORMAT;
    q = strchr(p, ' ');
    if (!q || q == p)
        return HIL_E_FORMAT;
    il = (size_t)(q - p);
    if (il >= HIL_CANDUMP_IFACE_MAX)
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
    *t = sec + frac;
    return HIL_OK;
}
