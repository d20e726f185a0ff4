"""ptable_set.py IN OUT ENTRY VALUE: sets every value of a 1 x 1 entry of an FRPT float64 parameter table
(libfrac/include/frac/ptable.h) and re-seals its CRC-32 trailer (IEEE 802.3, zlib.crc32)."""
import struct
import sys
import zlib

src, dst, name, value = sys.argv[1], sys.argv[2], sys.argv[3].encode(), float(sys.argv[4])
b = bytearray(open(src, "rb").read())
if b[:4] != b"FRPT" or struct.unpack_from("<H", b, 6)[0] != 2:
    sys.exit("ptable_set: %s is not a float64 FRPT table" % src)
found = False
for i in range(struct.unpack_from("<I", b, 12)[0]):
    o = 48 + 32 * i
    if b[o:o + 24].rstrip(b"\0") == name:
        rows, cols, off = struct.unpack_from("<HHI", b, o + 24)
        if (rows, cols) != (1, 1):
            sys.exit("ptable_set: entry %s is %d x %d, not 1 x 1" % (name.decode(), rows, cols))
        struct.pack_into("<d", b, off, value)
        found = True
if not found:
    sys.exit("ptable_set: no entry %s in %s" % (name.decode(), src))
struct.pack_into("<I", b, len(b) - 4, zlib.crc32(bytes(b[:-4])) & 0xFFFFFFFF)
open(dst, "wb").write(bytes(b))
