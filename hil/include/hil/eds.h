/* EDS (CiA 306 electronic data sheet) of a device, printed from its object
 * dictionary table (hil/od.h): the committed hil/drive.eds and hil/imu.eds
 * are this output (test hil_eds_matches_table), so the EDS a CANopen master
 * loads and the C code cannot disagree.
 *
 * Layout: [FileInfo], [DeviceInfo] (vendor, product and revision from
 * 0x1018, PDO counts from the 0x14xx/0x18xx objects, 1 Mbit/s as the only
 * bit rate), [DummyUsage], [Comments], the object lists [MandatoryObjects]
 * (0x1000, 0x1001, 0x1018), [OptionalObjects] (the rest of 0x1000-0x1FFF
 * and 0x6000-0xFFFF) and [ManufacturerObjects] (0x2000-0x5FFF), then one
 * section per object ([1018]) and per sub-index ([1018sub1]) with
 * ParameterName, ObjectType, DataType, AccessType, DefaultValue (integers
 * hex for unsigned, decimal for signed), PDOMapping and, when narrower than
 * the data type, LowLimit/HighLimit. No dates: the output is reproducible. */
#ifndef HIL_EDS_H
#define HIL_EDS_H
#include <stdio.h>
#include "hil/od.h"

/* Writes the EDS of od, file name `file_name` in [FileInfo]. Returns 0 or
 * HIL_E_IO when writing failed. */
int hil_eds_write(FILE *f, const struct hil_od *od, const char *file_name);

#endif
