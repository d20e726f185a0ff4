#!/usr/bin/env bash
# Cortex-M4F gate: cross-compile libfrac and the plc_blocks bodies with
# arm-none-eabi-gcc (single precision: frac_real = float, hard FPU ABI),
# archive them, and prove with arm-none-eabi-nm that nothing references the
# heap, stdio or file I/O. Prints the archive size. -fno-strict-aliasing:
# the plc_blocks bodies keep libfrac objects in IEC storage (plc_blocks/CMakeLists.txt).
# usage: cortex_m4.sh OUTDIR "INCLUDE_DIRS..." SOURCES...
set -euo pipefail
out=$1; shift
incs=$1; shift
mkdir -p "$out"; rm -f "$out"/*.o "$out"/libfrac_m4.a
CC=${ARM_CC:-arm-none-eabi-gcc}
command -v "$CC" >/dev/null || { echo "gate_cortex_m4: $CC not found (run: apt-get install gcc-arm-none-eabi libnewlib-arm-none-eabi)"; exit 1; }
iflags=(); for d in $incs; do iflags+=(-I"$d"); done
for src in "$@"; do
  obj="$out/$(basename "${src%.c}").o"
  "$CC" -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard -mthumb -Os -ffunction-sections \
        -std=c99 -fno-strict-aliasing -pedantic -Wall -Wextra -Werror -Wdouble-promotion -Wno-error=double-promotion \
        -DFRAC_REAL_FLOAT=1 "${iflags[@]}" -c "$src" -o "$obj"
done
arm-none-eabi-ar rcs "$out/libfrac_m4.a" "$out"/*.o
undef=$(arm-none-eabi-nm -u "$out/libfrac_m4.a" | awk 'NF==2 && $1=="U"{print $2}' | sort -u)
forbidden='^(malloc|calloc|realloc|free|printf|fprintf|sprintf|snprintf|vprintf|vfprintf|puts|putchar|fputs|fopen|fclose|fread|fwrite|fseek|ftell|fflush|fgets|fputc|fgetc|open|close|read|write|_sbrk|sbrk|exit|abort)$'
bad=$(printf '%s\n' "$undef" | grep -E "$forbidden" || true)
size=$(stat -c %s "$out/libfrac_m4.a")
echo "cortex-m4f archive: $out/libfrac_m4.a, $size bytes, $(ls "$out"/*.o | wc -l) objects"
arm-none-eabi-size -t "$out/libfrac_m4.a" | tail -1 | awk '{print "text+data+bss total: text=" $1 " data=" $2 " bss=" $3}'
echo "undefined symbols: $(printf '%s ' $undef)"
if [ -n "$bad" ]; then
  echo "FAIL: forbidden symbols referenced: $bad"
  exit 1
fi
echo "PASS: no malloc/free/printf/file I/O referenced"
