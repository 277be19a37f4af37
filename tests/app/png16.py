"""16-bit grey PNG (as the studio writes depth, millimetres) read by hand, for tests and benches that must not
depend on an imaging library: the PNG format's own chunks, zlib and row filters (None, Sub, Up, Average,
Paeth), nothing of the studio's. Also the scanlines of any 8-bit PNG (png_scanlines)."""
import struct
import zlib


def png_scanlines(data, bpp):
    """The rows of a non-interlaced PNG (bytes) as bytearrays, unfiltered; `bpp` bytes a pixel."""
    w, h = struct.unpack(">II", data[16:24])
    chunks, pos = b"", 8
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        if kind == b"IDAT":
            chunks += data[pos + 8:pos + 8 + n]
        pos += 12 + n
    raw = zlib.decompress(chunks)
    stride, rows, prev = bpp * w, [], bytearray(bpp * w)
    for v in range(h):
        kind, line = raw[v * (stride + 1)], bytearray(raw[v * (stride + 1) + 1:(v + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return rows


def read_png16(path):
    """(width, height, rows): rows[v][u] is the 16-bit value at column u, row v."""
    data = open(path, "rb").read()
    w, h, depth, colour = struct.unpack(">IIBB", data[16:26])
    if (depth, colour) != (16, 0):
        raise ValueError("%s: not a 16-bit grey PNG (bit depth %d, colour type %d)" % (path, depth, colour))
    rows = [[struct.unpack(">H", bytes(line[2 * u:2 * u + 2]))[0] for u in range(w)] for line in png_scanlines(data, 2)]
    return w, h, rows
