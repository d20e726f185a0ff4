/* ImuRead: the Cyclic #2 IMU acquisition program (ImuRead.h). */
#include "ImuRead.h"
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
    m->io_in.image = image_in;
    m->io_in.local = &m->in;
    m->io_in.size = sizeof m->in;
    m->io_out.image = image_out;
    m->io_out.local = &m->out;
    m->io_out.size = sizeof m->out;
    memset(prog, 0, sizeof *prog);
    prog->name = "ImuRead";
    prog->init = imuread_init;
    prog->cyclic = imuread_cyclic;
    prog->ctx = m;
    prog->inputs = &m->io_in;
    prog->n_inputs = 1;
    prog->outputs = &m->io_out;
    prog->n_outputs = 1;
}
