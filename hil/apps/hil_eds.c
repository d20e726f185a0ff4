/* hil_eds: prints the EDS (CiA 306) of the drive or the IMU from its C
 * object dictionary (hil/eds.h); hil/drive.eds and hil/imu.eds are its
 * output, checked by the test hil_eds_matches_table. */
#include <stdio.h>
#include <string.h>
#include "hil/drive.h"
#include "hil/eds.h"
#include "hil/imu.h"

int main(int argc, char **argv)
{
    const struct hil_od *od = NULL;
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        printf("usage: hil_eds drive|imu\nprints the device's EDS (CiA 306) from its object dictionary table\n");
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "drive") == 0)
        od = &hil_drive_od;
    else if (argc == 2 && strcmp(argv[1], "imu") == 0)
        od = &hil_imu_od;
    if (!od) {
        fprintf(stderr, "hil_eds: want one device, 'drive' or 'imu' (got %s)\n", argc > 1 ? argv[1] : "none");
        return 2;
    }
    if (hil_eds_write(stdout, od, od == &hil_drive_od ? "drive.eds" : "imu.eds") != 0) {
        perror("hil_eds: stdout");
        return 1;
    }
    return 0;
}
