/* hil_candump: the rig's candump-format logger (can-utils' candump is
 * dynamically linked in Debian; this one is static, for the QEMU initramfs,
 * and also listens on the UDP loopback bus). */
#include <stdlib.h>
#include <time.h>
#include "app_common.h"
#include "hil/candump.h"

int main(int argc, char **argv)
{
    struct app_opts o;
    struct hil_transport t;
    FILE *log = stdout;
    unsigned long long logged = 0;
    double last;
    app_parse(argc, argv, &o,
              "usage: hil_candump [options]\n"
              "Logs every frame of the bus in the candump -l format\n"
              "  (TIME) IFACE ID#DATA   (TIME: wall clock, seconds since 1970)\n"
              "  --out FILE          log file (default stdout)\n");
    app_open_bus(&t, o.bus);
    if (o.out && !(log = fopen(o.out, "w"))) {
        perror(o.out);
        return 1;
    }
    last = app_now();
    for (;;) {
        struct hil_can_frame f;
        struct timespec ts;
        char line[HIL_CANDUMP_LINE_MAX];
        int st = hil_transport_recv(&t, &f, 100000);
        if (st == HIL_E_TIMEOUT) {
            if (app_now() - last > o.idle_exit)
                break;
            continue;
        }
        last = app_now();
        if (st == HIL_E_IO)
            break;
        if (st != HIL_OK)
            continue;
        clock_gettime(CLOCK_REALTIME, &ts);
        if (hil_candump_format(line, sizeof line, (double)ts.tv_sec + 1e-9 * ts.tv_nsec, t.name, &f) > 0) {
            fputs(line, log);
            logged++;
        }
    }
    if (log != stdout)
        fclose(log);
    else
        fflush(log);
    fprintf(stderr, "HIL_STATS node=candump logged=%llu rx_invalid=%llu rx_dropped=%llu\n", logged,
            (unsigned long long)t.rx_invalid, (unsigned long long)t.rx_dropped);
    hil_transport_close(&t);
    return 0;
}
