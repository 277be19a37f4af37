#!/usr/bin/env python3
"""Test-side writer of 360 video metadata: copies an MP4 made by ffmpeg (moov after mdat, so no chunk offset
moves) and adds Google's Spherical Video V2 boxes (st3d, sv3d > svhd, proj > prhd + equi | cbmp) to the
video track's sample entry, or the V1 XML (uuid ffcc8263-f855-4a93-8814-587a02521fdd) to the video track.
Written from the specifications, independently of the reader under test; ffprobe checks the result.

usage: spherical_mp4_writer.py IN OUT [--v2] [--v1] [--yaw D] [--pitch D] [--roll D]
       [--projection equirectangular|cubemap] [--bounds T,B,L,R] [--stereo 0|1|2] [--software NAME]
       [--crop FULL_W,FULL_H,LEFT,TOP,W,H]
"""
import argparse
import struct
import sys

V1_UUID = bytes.fromhex("ffcc8263f8554a938814587a02521fdd")
VISUAL_SAMPLE_ENTRY_HEADER = 78


def box(kind, payload):
    return struct.pack(">I", 8 + len(payload)) + kind + payload


def full_box(kind, payload, version=0, flags=0):
    return box(kind, struct.pack(">I", (version << 24) | flags) + payload)


def children(data, start, end):
    """(type, box start, payload start, box end) of the boxes laid out in data[start:end]."""
    out = []
    at = start
    while at + 8 <= end:
        size, kind = struct.unpack(">I4s", data[at:at + 8])
        header = 8
        if size == 1:
            size = struct.unpack(">Q", data[at + 8:at + 16])[0]
            header = 16
        elif size == 0:
            size = end - at
        if size < header or at + size > end:
            raise ValueError("bad box %r at %d" % (kind, at))
        out.append((kind, at, at + header, at + size))
        at += size
    return out


def find(boxes, kind):
    for b in boxes:
        if b[0] == kind:
            return b
    return None


def v2_boxes(a):
    boxes = b""
    if a.stereo is not None:
        boxes += full_box(b"st3d", struct.pack(">B", a.stereo))
    fixed = lambda deg: int(round(deg * 65536))
    prhd = full_box(b"prhd", struct.pack(">iii", fixed(a.yaw), fixed(a.pitch), fixed(a.roll)))
    if a.projection == "cubemap":
        shape = full_box(b"cbmp", struct.pack(">II", 0, 0))
    else:
        t, bt, l, r = (int(round(float(v) * 2**32)) for v in a.bounds.split(","))
        shape = full_box(b"equi", struct.pack(">IIII", t, bt, l, r))
    svhd = full_box(b"svhd", a.software.encode() + b"\0")
    return boxes + box(b"sv3d", svhd + box(b"proj", prhd + shape))


def v1_box(a):
    tags = [("Spherical", "true"), ("Stitched", "true"), ("StitchingSoftware", a.software),
            ("ProjectionType", "equirectangular"), ("InitialViewHeadingDegrees", "%g" % a.yaw),
            ("InitialViewPitchDegrees", "%g" % a.pitch), ("InitialViewRollDegrees", "%g" % a.roll)]
    if a.crop:
        names = ["FullPanoWidthPixels", "FullPanoHeightPixels", "CroppedAreaLeftPixels", "CroppedAreaTopPixels",
                 "CroppedAreaImageWidthPixels", "CroppedAreaImageHeightPixels"]
        tags += list(zip(names, a.crop.split(",")))
    xml = ('<?xml version="1.0"?><rdf:SphericalVideo xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" '
           'xmlns:GSpherical="http://ns.google.com/videos/1.0/spherical/">' +
           "".join("<GSpherical:%s>%s</GSpherical:%s>" % (k, v, k) for k, v in tags) +
           "</rdf:SphericalVideo>")
    return box(b"uuid", V1_UUID + xml.encode())


def main():
    p = argparse.ArgumentParser()
    p.add_argument("input")
    p.add_argument("output")
    p.add_argument("--v2", action="store_true")
    p.add_argument("--v1", action="store_true")
    p.add_argument("--yaw", type=float, default=0.0)
    p.add_argument("--pitch", type=float, default=0.0)
    p.add_argument("--roll", type=float, default=0.0)
    p.add_argument("--projection", default="equirectangular")
    p.add_argument("--bounds", default="0,0,0,0")
    p.add_argument("--stereo", type=int, default=None)
    p.add_argument("--software", default="plenopath test writer")
    p.add_argument("--crop", default=None)
    a = p.parse_args()

    data = bytearray(open(a.input, "rb").read())
    top = children(data, 0, len(data))
    moov, mdat = find(top, b"moov"), find(top, b"mdat")
    if moov is None or mdat is None or moov[1] < mdat[1]:
        sys.exit("need an MP4 with its moov box after mdat (ffmpeg's default)")
    # The video track and the path down to its first sample entry.
    for trak in (b for b in children(data, moov[2], moov[3]) if b[0] == b"trak"):
        trak_boxes = children(data, trak[2], trak[3])
        mdia = find(trak_boxes, b"mdia")
        mdia_boxes = children(data, mdia[2], mdia[3])
        hdlr = find(mdia_boxes, b"hdlr")
        if data[hdlr[2] + 8:hdlr[2] + 12] != b"vide":
            continue
        minf = find(mdia_boxes, b"minf")
        stbl = find(children(data, minf[2], minf[3]), b"stbl")
        stsd = find(children(data, stbl[2], stbl[3]), b"stsd")
        entry = children(data, stsd[2] + 8, stsd[3])[0]
        break
    else:
        sys.exit("no video track")

    # Insert at the end of the sample entry (V2) and at the end of the track (V1), the later position first so
    # that the other is still where it was measured; every enclosing box grows by what went in.
    inserts = []
    if a.v2:
        inserts.append((entry[3], v2_boxes(a), [moov, trak, mdia, minf, stbl, stsd, entry]))
    if a.v1:
        inserts.append((trak[3], v1_box(a), [moov, trak]))
    for position, payload, ancestors in sorted(inserts, key=lambda i: -i[0]):
        data[position:position] = payload
        for b in ancestors:
            size = struct.unpack(">I", data[b[1]:b[1] + 4])[0]
            if size == 1:
                sys.exit("64-bit box sizes are not handled by this writer")
            data[b[1]:b[1] + 4] = struct.pack(">I", size + len(payload))
    open(a.output, "wb").write(data)


if __name__ == "__main__":
    main()
