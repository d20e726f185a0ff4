/* Whole-file reading for the rig's binary tables (plant.table, ctrl.table). */
#ifndef HIL_FILE_H
#define HIL_FILE_H

/* The whole file at `path` in a new malloc'd buffer (the caller frees it),
 * its length in *size. NULL when the file cannot be opened or read, or is
 * larger than `max` bytes. */
unsigned char *hil_read_file(const char *path, unsigned long max, unsigned long *size);

#endif
