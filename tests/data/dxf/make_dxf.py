#!/usr/bin/env python3
"""Writes the small DXF files the importer tests read (run from this folder). Hand-made so the expected
geometry can be computed by hand in tests/processing/plan/dxf_import_test.cpp."""


def dxf(entities, insunits=None, layers=(), blocks=()):
    out = ["0", "SECTION", "2", "HEADER", "9", "$ACADVER", "1", "AC1015"]
    if insunits is not None:
        out += ["9", "$INSUNITS", "70", str(insunits)]
    out += ["0", "ENDSEC"]
    out += ["0", "SECTION", "2", "TABLES", "0", "TABLE", "2", "LAYER", "70", str(len(layers))]
    for name, colour in layers:
        out += ["0", "LAYER", "2", name, "70", "0", "62", str(colour), "6", "CONTINUOUS"]
    out += ["0", "ENDTAB", "0", "ENDSEC"]
    out += ["0", "SECTION", "2", "BLOCKS"]
    for name, base, body in blocks:
        out += ["0", "BLOCK", "8", "0", "2", name, "70", "0", "10", str(base[0]), "20", str(base[1]), "30", "0",
                "3", name]
        out += body
        out += ["0", "ENDBLK", "8", "0"]
    out += ["0", "ENDSEC", "0", "SECTION", "2", "ENTITIES"]
    out += entities
    out += ["0", "ENDSEC", "0", "EOF"]
    return "\n".join(out) + "\n"


def line(layer, a, b):
    return ["0", "LINE", "8", layer, "10", str(a[0]), "20", str(a[1]), "30", "0", "11", str(b[0]), "21", str(b[1]),
            "31", "0"]


def write(name, text):
    with open(name, "w", newline="\n") as f:
        f.write(text)


# Millimetres: a 10 m square on WALLS, a table edge on FURNITURE, a duplicated wall and a zero-length line.
write("lines_mm.dxf", dxf(
    line("WALLS", (0, 0), (10000, 0)) + line("WALLS", (10000, 0), (10000, 10000)) +
    line("WALLS", (10000, 10000), (0, 10000)) + line("WALLS", (0, 10000), (0, 0)) +
    line("WALLS", (0, 0), (10000, 0)) + line("WALLS", (5000, 5000), (5000, 5000)) +
    line("FURNITURE", (2000, 2000), (3000, 2000)),
    insunits=4, layers=[("WALLS", 7), ("FURNITURE", 3), ("HIDDEN", -5)]))

# Metres: closed LWPOLYLINE (0,0) (4,0) bulge 1 (half circle to (4,2), centre (4,1)) (0,2).
write("lwpolyline_bulge.dxf", dxf(
    ["0", "LWPOLYLINE", "8", "WALLS", "90", "4", "70", "1",
     "10", "0", "20", "0", "10", "4", "20", "0", "42", "1", "10", "4", "20", "2", "10", "0", "20", "2"],
    insunits=6, layers=[("WALLS", 7)]))

# Centimetres: old-style closed POLYLINE of four VERTEX entities, 1 m x 0.5 m.
write("old_polyline_cm.dxf", dxf(
    ["0", "POLYLINE", "8", "WALLS", "66", "1", "70", "1", "10", "0", "20", "0", "30", "0"] +
    sum((["0", "VERTEX", "8", "WALLS", "10", str(x), "20", str(y), "30", "0"]
         for x, y in [(0, 0), (100, 0), (100, 50), (0, 50)]), []) +
    ["0", "SEQEND", "8", "WALLS"],
    insunits=5, layers=[("WALLS", 7)]))

# Metres: ARC centre (0,0) r 2 from 0 to 90 deg; CIRCLE centre (10,0) r 1; full ELLIPSE centre (20,0),
# major (3,0), ratio 0.5; ARC with extrusion (0,0,-1), OCS centre (5,5) r 1, 0..90 deg -> WCS centre (-5,5).
write("curves.dxf", dxf(
    ["0", "ARC", "8", "WALLS", "10", "0", "20", "0", "30", "0", "40", "2", "50", "0", "51", "90"] +
    ["0", "CIRCLE", "8", "COLUMNS", "10", "10", "20", "0", "30", "0", "40", "1"] +
    ["0", "ELLIPSE", "8", "WALLS", "10", "20", "20", "0", "30", "0", "11", "3", "21", "0", "31", "0",
     "40", "0.5", "41", "0", "42", "6.283185307179586"] +
    ["0", "ARC", "8", "MIRRORED", "10", "5", "20", "5", "30", "0", "40", "1", "50", "0", "51", "90",
     "210", "0", "220", "0", "230", "-1"],
    insunits=6, layers=[("WALLS", 7), ("COLUMNS", 1), ("MIRRORED", 2)]))

# Metres: quadratic clamped B-spline (a Bezier) through control points (0,0) (1,2) (2,0): B(1/2) = (1,1).
write("spline.dxf", dxf(
    ["0", "SPLINE", "8", "WALLS", "70", "8", "71", "2", "72", "6", "73", "3", "74", "0",
     "40", "0", "40", "0", "40", "0", "40", "1", "40", "1", "40", "1",
     "10", "0", "20", "0", "30", "0", "10", "1", "20", "2", "30", "0", "10", "2", "20", "0", "30", "0"],
    insunits=6, layers=[("WALLS", 7)]))

# Inches: block TICK = LINE (0,0)-(0,1) on layer 0; block COL = LINE (0,0)-(1,0) on layer 0 plus TICK
# inserted at (1,0). Model space: COL at (10,0), scale (-2,1), rotation 90 deg, 3 columns x 2 rows spaced
# 5 and 4, on layer COLUMNS. A block point p lands at (10,0) + R90 * (S p + (5c, 4r)).
write("blocks_in.dxf", dxf(
    ["0", "INSERT", "8", "COLUMNS", "2", "COL", "10", "10", "20", "0", "30", "0", "41", "-2", "42", "1", "43", "1",
     "50", "90", "70", "3", "71", "2", "44", "5", "45", "4"],
    insunits=1, layers=[("COLUMNS", 1)],
    blocks=[("TICK", (0, 0), line("0", (0, 0), (0, 1))),
            ("COL", (0, 0), line("0", (0, 0), (1, 0)) +
             ["0", "INSERT", "8", "0", "2", "TICK", "10", "1", "20", "0", "30", "0"])]))

# Feet: one 10 ft wall; block with a base point (1,1): its LINE (1,1)-(2,1) inserted at (0,5) -> (0,5)-(1,5).
write("feet.dxf", dxf(
    line("WALLS", (0, 0), (10, 0)) +
    ["0", "INSERT", "8", "WALLS", "2", "B", "10", "0", "20", "5", "30", "0"],
    insunits=2, layers=[("WALLS", 7)], blocks=[("B", (1, 1), line("0", (1, 1), (2, 1)))]))

# Labels: TEXT and MTEXT, plus one wall so the plan has geometry.
write("text.dxf", dxf(
    line("WALLS", (0, 0), (5, 0)) +
    ["0", "TEXT", "8", "ANNOTATION", "10", "1", "20", "2", "30", "0", "40", "0.25", "1", "Kitchen"] +
    ["0", "MTEXT", "8", "ANNOTATION", "10", "3", "20", "4", "30", "0", "40", "0.5", "1", "Hall"],
    insunits=6, layers=[("WALLS", 7), ("ANNOTATION", 2)]))

# Malformed inputs.
good = open("lines_mm.dxf").read()
write("truncated.dxf", good[: len(good) // 2])
write("bad_group_code.dxf", good.replace("0\nLINE\n8\nWALLS\n10\n0\n", "0\nLINE\n8\nWALLS\nxx\n0\n", 1))
write("bad_number.dxf", good.replace("\n10\n10000\n", "\n10\n1O000\n", 1))
write("no_geometry.dxf", dxf([], insunits=6, layers=[("WALLS", 7)]))
write("absurd.dxf", dxf(line("WALLS", (0, 0), (1e13, 0)), insunits=6, layers=[("WALLS", 7)]))
with open("binary.dxf", "wb") as f:
    f.write(b"AutoCAD Binary DXF\r\n\x1a\x00" + bytes(range(256)))
