/* CAN frame checks, status names and little-endian field access. */
#include <string.h>
#include "hil/can.h"

const char *hil_status_str(int status)
{
    switch (status) {
    case HIL_OK: return "ok";
    case HIL_E_ARG: return "bad argument";
    case HIL_E_DLC: return "wrong DLC";
    case HIL_E_UNKNOWN_ID: return "unknown identifier";
    case HIL_E_FORMAT: return "malformed frame";
    case HIL_E_IO: return "I/O error";
    case HIL_E_TIMEOUT: return "timeout";
    case HIL_E_UNSUPPORTED: return "not supported by this kernel";
    case HIL_E_RANGE: return "value out of range";
    case HIL_E_FULL: return "buffer too small";
    case HIL_E_STATE: return "not allowed in this state";
    default: return "unknown status";
    }
}

int hil_can_frame_check(const struct hil_can_frame *f)
{
    if (!f)
        return HIL_E_ARG;
    if (f->dlc > HIL_CAN_MAX_DLC)
        return HIL_E_DLC;
    if (f->id & (HIL_CAN_RTR_FLAG | HIL_CAN_ERR_FLAG))
        return HIL_E_FORMAT;
    if (f->id & HIL_CAN_EFF_FLAG)
        return (f->id & ~(HIL_CAN_EFF_FLAG | HIL_CAN_EFF_MASK)) ? HIL_E_FORMAT : HIL_OK;
    return (f->id & ~HIL_CAN_SFF_MASK) ? HIL_E_FORMAT : HIL_OK;
}

uint16_t hil_get_u16(const uint8_t *p) { return (uint16_t)(p[0] | (p[1] << 8)); }

uint32_t hil_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

void hil_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

void hil_put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
    p[2] = (uint8_t)((v >> 16) & 0xFFu);
    p[3] = (uint8_t)(v >> 24);
}

/* IEEE 754 binary32 on every platform the rig targets; the bit pattern is
 * moved through memcpy so no aliasing rule is broken. */
float hil_get_f32(const uint8_t *p)
{
    uint32_t u = hil_get_u32(p);
    float v;
    memcpy(&v, &u, sizeof v);
    return v;
}

void hil_put_f32(uint8_t *p, float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    hil_put_u32(p, u);
}
