#!/usr/bin/env python3
"""Writes multi-resolution cube tiles into an exported tour, for the player's tests (test-only).

usage: make_cube_tiles.py PACKAGE_DIR --face-size N --tile-size T

Follows tour.json's "tiles" (resources/schema/tour.schema.json): per keyframe a folder tiles/<frame>/ with
"<level>/<face>/<y>_<x>.jpg"; levels coarsest first, level 0 a fallback_only face of T/2, then T, 2T, ... up to
N (each twice the previous); face pixel (x, y) of a face of size s looks along
forward + (2(x + 0.5)/s - 1) right + (2(y + 0.5)/s - 1) down in the camera frame (+x forward = the image's
centre column, +y left, +z up). The faces are cut here, independently of the player, from each keyframe's full
equirectangular JPEG with numpy (bilinear) and written by ImageMagick; tour.json and tour.js get the
"tiles" entries.
"""
import json, os, subprocess, sys
import numpy as np

# rig/spherical.h's cube_face_axes: forward, right, down in the camera frame.
FACES = [('f', (1, 0, 0), (0, -1, 0), (0, 0, -1)), ('r', (0, -1, 0), (-1, 0, 0), (0, 0, -1)),
         ('b', (-1, 0, 0), (0, 1, 0), (0, 0, -1)), ('l', (0, 1, 0), (1, 0, 0), (0, 0, -1)),
         ('u', (0, 0, 1), (0, -1, 0), (1, 0, 0)), ('d', (0, 0, -1), (0, -1, 0), (-1, 0, 0))]


def read_image(path):
    """RGB uint8 array of any image ImageMagick reads (via binary PPM)."""
    ppm = subprocess.run(['convert', path, '-depth', '8', 'ppm:-'], check=True, capture_output=True).stdout
    fields, at = [], 0
    while len(fields) < 4:  # P6, width, height, maxval: whitespace-separated, then one whitespace byte
        while ppm[at:at + 1].isspace():
            at += 1
        end = at
        while not ppm[end:end + 1].isspace():
            end += 1
        fields.append(ppm[at:end])
        at = end
    w, h = int(fields[1]), int(fields[2])
    return np.frombuffer(ppm[at + 1:at + 1 + w * h * 3], dtype=np.uint8).reshape(h, w, 3)


def cut_face(equirect, forward, right, down, size):
    h, w, _ = equirect.shape
    c = (np.arange(size) + 0.5) * 2.0 / size - 1.0
    a, b = np.meshgrid(c, c)  # a along right (columns), b along down (rows)
    d = [forward[i] + a * right[i] + b * down[i] for i in range(3)]
    azimuth = np.arctan2(-d[1], d[0])           # grows to the right (+y is left)
    elevation = np.arctan2(d[2], np.hypot(d[0], d[1]))
    x = (azimuth + np.pi) / (2 * np.pi) * w - 0.5  # column 0 is azimuth -180 deg
    y = (np.pi / 2 - elevation) / np.pi * h - 0.5
    x0 = np.floor(x).astype(int); y0 = np.clip(np.floor(y).astype(int), 0, h - 1)
    fx = (x - x0)[..., None]; fy = np.clip(y - y0, 0, 1)[..., None]
    y1 = np.clip(y0 + 1, 0, h - 1)
    xa, xb = x0 % w, (x0 + 1) % w
    img = equirect.astype(np.float32)
    top = img[y0, xa] * (1 - fx) + img[y0, xb] * fx
    bottom = img[y1, xa] * (1 - fx) + img[y1, xb] * fx
    return np.clip(top * (1 - fy) + bottom * fy + 0.5, 0, 255).astype(np.uint8)


def write_tiles(face, folder, name, levels):
    size = face.shape[0]
    ppm = b'P6 %d %d 255\n' % (size, size) + face.tobytes()
    for level, (s, t) in enumerate(levels):
        out = os.path.join(folder, str(level), name)
        os.makedirs(out, exist_ok=True)
        # ImageMagick numbers the crops row by row: tile k is row k // n, column k % n.
        subprocess.run(['convert', 'ppm:-', '-filter', 'Triangle', '-resize', '%dx%d!' % (s, s), '-crop',
                        '%dx%d' % (t, t), '+repage', '-quality', '90', os.path.join(out, 'tile_%d.jpg')],
                       input=ppm, check=True)
        n = -(-s // t)
        for k in range(n * n):
            os.rename(os.path.join(out, 'tile_%d.jpg' % k), os.path.join(out, '%d_%d.jpg' % (k // n, k % n)))


def main():
    if len(sys.argv) != 6 or sys.argv[2] != '--face-size' or sys.argv[4] != '--tile-size':
        print(__doc__)
        sys.exit(2)
    package, face_size, tile = sys.argv[1], int(sys.argv[3]), int(sys.argv[5])
    levels = [(tile // 2, tile // 2)]
    s = tile
    while s <= face_size:
        levels.append((s, tile))
        s *= 2
    with open(os.path.join(package, 'tour.json')) as f:
        tour = json.load(f)
    for k in tour['keyframes']:
        equirect = read_image(os.path.join(package, k['full']))
        folder = 'tiles/%06d' % k['frame']
        for name, forward, right, down in FACES:
            write_tiles(cut_face(equirect, forward, right, down, face_size), os.path.join(package, folder), name, levels)
        k['tiles'] = folder
    tour['tiles'] = {'projection': 'cube', 'path': '{level}/{face}/{y}_{x}.jpg',
                     'levels': [dict({'size': s, 'tile_size': t}, **({'fallback_only': True} if i == 0 else {}))
                                for i, (s, t) in enumerate(levels)],
                     'faces': [{'name': n, 'forward': list(fw), 'right': list(r), 'down': list(d)}
                               for n, fw, r, d in FACES]}
    with open(os.path.join(package, 'tour.json'), 'w') as f:
        json.dump(tour, f, indent=1)
    with open(os.path.join(package, 'tour.js'), 'w') as f:
        f.write('window.PLENOPATH_TOUR = ' + json.dumps(tour) + ';\n')
    print('tiles: %d keyframes, levels %s' % (len(tour['keyframes']), [s for s, _ in levels]))


if __name__ == '__main__':
    main()
