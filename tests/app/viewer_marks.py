"""Equirectangular test panoramas with coloured discs at known directions, drawn from ARCHITECTURE.md's
formulas alone (column 0 = azimuth -180 deg, azimuth growing to the right, row 0 = zenith) and written as
8-bit RGB PNG by hand (zlib), so that nothing of the studio's decides where a mark lands.

Every frame holds four compass marks fixed in the world (plan frame, X east, Y north): east red, north white,
west blue, south green, each at azimuth heading - world_angle. The first frame also holds marks fixed in its
image, above and below the horizon and off the face centres, to tell every cube face's orientation apart.
"""
import math
import struct
import zlib

from png16 import png_scanlines  # the one hand-written PNG row decoder of the tests

COLOURS = {
    'red': (230, 20, 20), 'green': (20, 200, 20), 'blue': (20, 40, 230), 'white': (250, 250, 250),
    'yellow': (240, 230, 20), 'magenta': (230, 20, 230), 'cyan': (20, 220, 230), 'orange': (250, 140, 10),
    'purple': (120, 20, 200),
}
BACKGROUND = ((90, 90, 90), (150, 150, 150))  # a 10-degree checkerboard: never blank, never a mark's colour
RADIUS_DEG = 4.0

# World marks: world angle (deg, CCW from +X) -> colour.
WORLD_MARKS = {0.0: 'red', 90.0: 'white', 180.0: 'blue', -90.0: 'green'}
# Image marks of the first frame: (azimuth, elevation) in degrees -> colour.
IMAGE_MARKS = {(45.0, 20.0): 'yellow', (0.0, 60.0): 'magenta', (90.0, 60.0): 'cyan',
               (0.0, -60.0): 'orange', (-90.0, -60.0): 'purple'}


def wrap180(a):
    return (a + 180.0) % 360.0 - 180.0


def marks_of_frame(heading_deg, first):
    """[(azimuth, elevation, colour name)] of a frame with the given heading."""
    marks = [(wrap180(heading_deg - phi), 0.0, c) for phi, c in WORLD_MARKS.items()]
    if first:
        marks += [(az, el, c) for (az, el), c in IMAGE_MARKS.items()]
    return marks


def bearing(az, el):
    a, e = math.radians(az), math.radians(el)
    return (math.cos(e) * math.cos(a), -math.cos(e) * math.sin(a), math.sin(e))


def draw(width, marks):
    """Rows of RGB bytes."""
    height = width // 2
    cell = width / 36.0
    rows = []
    for v in range(height):
        even = int(v / cell) % 2
        row = bytearray()
        for k in range(36):
            grey = BACKGROUND[(k + even) % 2]
            n = int(round((k + 1) * cell)) - int(round(k * cell))
            row += bytes(grey) * n
        rows.append(row)
    cos_r = math.cos(math.radians(RADIUS_DEG))
    for az, el, name in marks:
        colour = bytes(COLOURS[name])
        b = bearing(az, el)
        v0 = max(0, int((90.0 - el - RADIUS_DEG - 1) / 180.0 * height))
        v1 = min(height, int((90.0 - el + RADIUS_DEG + 1) / 180.0 * height) + 1)
        for v in range(v0, v1):
            e = 90.0 - (v + 0.5) / height * 180.0
            for u in range(width):
                a = (u + 0.5) / width * 360.0 - 180.0
                if abs(wrap180(a - az)) > 90:
                    continue
                p = bearing(a, e)
                if p[0] * b[0] + p[1] * b[1] + p[2] * b[2] >= cos_r:
                    rows[v][3 * u:3 * u + 3] = colour
    return rows


def write_png(path, rows):
    height, width = len(rows), len(rows[0]) // 3
    raw = b''.join(b'\0' + bytes(r) for r in rows)

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(raw, 6)) + chunk(b'IEND', b''))


def read_png_rgb(data):
    """(width, height, rows of RGB tuples) of an 8-bit RGB or RGBA PNG given as bytes (what Chromium writes)."""
    w, h, depth, colour = struct.unpack('>IIBB', data[16:26])
    if depth != 8 or colour not in (2, 6):
        raise ValueError('not an 8-bit RGB/RGBA PNG (depth %d, colour type %d)' % (depth, colour))
    bpp = 3 if colour == 2 else 4
    rows = [[tuple(line[bpp * u:bpp * u + 3]) for u in range(w)] for line in png_scanlines(data, bpp)]
    return w, h, rows


def classify(rgb):
    """The nearest of the marks' colours and the background's greys: a name, or 'background'."""
    best, name = None, None
    for n, c in list(COLOURS.items()) + [('background', g) for g in BACKGROUND]:
        d = sum((x - y) ** 2 for x, y in zip(rgb, c))
        if best is None or d < best:
            best, name = d, n
    return name
