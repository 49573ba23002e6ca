#!/usr/bin/env python3
"""forge_frame.py IN OUT KIND - rewrite one record of a recorded lt-stream session (docs/stream.md)
into a CRC-valid frame whose content contradicts the HELLO or itself, for tests/run.d/stream.sh:
  tile_out    the first TILE's tile index -> 999 (the 64x64 image has 16 tiles)
  tile_twice  the second TILE reports the first TILE's (frame, tile) under its own sequence number
  rays        the first TILE's rays -> 65535 (a 16x16 tile has 256 pixels)
  sum_tiles   the first SUMMARY's tiles -> 65535
  hello_zero  the HELLO's tile size -> 0x0
  image_out   the first IMAGE's tile index -> 999
  tile_len0   the first TILE with a payload of 0 bytes (a TILE is 40)
  cut         the first 5 frames and 30 bytes of the 6th: the input ends inside a frame
Prints the sequence number of the forged frame. Test tool, not shipped."""
import struct
import sys


def crc32c(b):
    c = 0xFFFFFFFF
    for x in b:
        c ^= x
        for _ in range(8):
            c = (c >> 1) ^ (0x82F63B78 if c & 1 else 0)
    return c ^ 0xFFFFFFFF


def reframe(f, payload):
    b = bytes(f[:6]) + bytes([len(payload), 0]) + payload.ljust(52, b"\0")
    return b + struct.pack("<I", crc32c(b))


def main():
    src, dst, kind = sys.argv[1:4]
    data = open(src, "rb").read()
    fr = [bytearray(data[i:i + 64]) for i in range(0, len(data), 64)]
    tiles = [i for i, f in enumerate(fr) if f[3] == 2]
    sums = [i for i, f in enumerate(fr) if f[3] == 3]
    if kind == "tile_out":
        i, off, val = tiles[0], 2, 999
    elif kind == "tile_twice":
        i = tiles[1]
        p = bytearray(fr[i][8:8 + fr[i][6]])
        p[0:4] = fr[tiles[0]][8:12]
        fr[i] = bytearray(reframe(fr[i], bytes(p)))
        off = None
    elif kind == "rays":
        i, off, val = tiles[0], 4, 65535
    elif kind == "sum_tiles":
        i, off, val = sums[0], 2, 65535
    elif kind == "hello_zero":
        i = 0
        p = bytearray(fr[0][8:8 + fr[0][6]])
        p[1] = p[2] = 0
        fr[0] = bytearray(reframe(fr[0], bytes(p)))
        off = None
    elif kind == "image_out":
        i, off, val = [k for k, f in enumerate(fr) if f[3] == 5][0], 2, 999
    elif kind == "tile_len0":
        i = tiles[0]
        fr[i] = bytearray(reframe(fr[i], b""))
        off = None
    elif kind == "cut":
        open(dst, "wb").write(b"".join(bytes(f) for f in fr[:5]) + bytes(fr[5][:30]))
        print(struct.unpack("<H", bytes(fr[4][4:6]))[0])
        return
    else:
        sys.exit("forge_frame.py: unknown kind " + kind)
    if off is not None:
        p = bytearray(fr[i][8:8 + fr[i][6]])
        struct.pack_into("<H", p, off, val)
        fr[i] = bytearray(reframe(fr[i], bytes(p)))
    open(dst, "wb").write(b"".join(bytes(f) for f in fr))
    print(struct.unpack("<H", bytes(fr[i][4:6]))[0])


main()
