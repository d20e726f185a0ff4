/* ImuRead: the Cyclic #2 IMU acquisition program (ImuRead.h). */
#include "ImuRead.h"
#include "plcprog.h"
#include "frac/frac_types.h"

#include <string.h>

void imuread_init(void *ctx)
{
    imuread *m = (imuread *)ctx;
    memset(&m->out, 0, sizeof m->out);
    m->frame_old = m->in.FrameCounter;
}

void imuread_cyclic(void *ctx)
{
    imuread *m = (imuread *)ctx;
    if (m->in.FrameCounter == m->frame_old) {
        return;
    }
    m->frame_old = m->in.FrameCounter;
    if (!FRAC_ISFINITE(m->in.RawRate)) {
        m->out.Dropped++;
        return;
    }
    m->out.TipRate = m->in.RawRate * m->scale;
    m->out.ImuCounter++;
}

void imuread_program(imuread *m, plc_program *prog, REAL scale, imuread_inputs *image_in,
                     imuread_outputs *image_out)
{
    memset(m, 0, sizeof *m);
    m->scale = scale;
    plcprog_io(&m->io_in, image_in, &m->in, sizeof m->in);
    plcprog_io(&m->io_out, image_out, &m->out, sizeof m->out);
    plcprog_describe(prog, "ImuRead", imuread_init, imuread_cyclic, NULL, m, &m->io_in, 1, &m->io_out);
}
