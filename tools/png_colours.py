#!/usr/bin/env python3
"""png_colours.py PNG - the number of distinct pixel values of an 8-bit PNG (no interlace), for
tests that need to know an image is not flat (a heatmap whose values were all zero has the colour
of zero and the legend's only). Prints the count."""
import struct
import sys
import zlib


def colours(path):
    d = open(path, 'rb').read()
    i, idat, w, h, bpp = 8, b'', 0, 0, 1
    while i < len(d):
        n = struct.unpack('>I', d[i:i + 4])[0]
        t, c = d[i + 4:i + 8], d[i + 8:i + 8 + n]
        if t == b'IHDR':
            w, h, depth, ctype = struct.unpack('>IIBB', c[:10])
            bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype] * depth // 8
        elif t == b'IDAT':
            idat += c
        i += 12 + n
    raw, stride, prev, seen, p = zlib.decompress(idat), w * bpp, bytearray(w * bpp), set(), 0
    for _ in range(h):
        f, line = raw[p], bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        seen.update(bytes(line[x:x + bpp]) for x in range(0, stride, bpp))
        prev = line
    return len(seen)


print(colours(sys.argv[1]))
