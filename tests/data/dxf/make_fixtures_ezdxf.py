#!/usr/bin/python3
"""Writes the DXF fixtures of issue 16 with python3-ezdxf (Debian: /usr/bin/python3), each with the expected
result beside it (NAME.expected.json), for tests/processing/plan/dxf_fixtures_test.cpp.

Run once from anywhere: /usr/bin/python3 tests/data/dxf/make_fixtures_ezdxf.py; the outputs are committed.

The expectations come from what this script constructs (the numbers it draws with), never from the importer:
  units, units_source_any_of   units the importer must choose, and how ("header", "inferred")
  size_m, size_tolerance_m     the building's size in metres (plan extents, strays left out), +-1 cm
  extents_dxf_m                the building's extents in metres in the DXF frame (plan + dxf_origin_m)
  layer_extents_dxf_m          the same for single layers (furniture placed by nested/mirrored inserts)
  occluder_layers              layers that must block sight (proposal, no options given)
  not_occluder_layers          layers that must not
  layers                       layer names (UTF-8) the plan must have
  labels                       label texts (UTF-8) the plan must have; a list = any one of these spellings
  entities_by_layer            model-space entities read, per layer and kind (INSERT counts once)
  stray_entities               entities reported as far from the drawing's bulk
  recentred                    whether dxf_origin_m must be non-zero (far-from-origin drawing)
  version, binary, codepage    what the report must say about the file
"""
import json
import math
import os

import ezdxf
import ezdxf.tools.codepage

# Same bytes on every run (dates and GUIDs fixed), so a re-run shows only real changes.
ezdxf.options.write_fixed_meta_data_for_testing = True
HERE = os.path.dirname(os.path.abspath(__file__))
MM = 0.001


class Plan:
    """An ezdxf drawing plus the record of what was put into its model space."""

    def __init__(self, name, version, insunits=None, encoding=None):
        self.name = name
        self.doc = ezdxf.new(version, setup=False)
        if encoding:  # the strings' bytes (R2000 and older) and the header that names them
            self.doc.encoding = encoding
            self.doc.header["$DWGCODEPAGE"] = ezdxf.tools.codepage.tocodepage(encoding)
        if insunits is not None:
            self.doc.header["$INSUNITS"] = insunits
        self.msp = self.doc.modelspace()
        self.counts = {}
        self.labels = []
        self.box = {}  # layer -> [minx, miny, maxx, maxy] in drawing units, strays left out
        self.stray = 0
        self.expect = {}

    def layer(self, name, color=7, **attribs):
        if name not in self.doc.layers:
            self.doc.layers.add(name, color=color, **attribs)

    def _count(self, layer, kind):
        self.counts.setdefault(layer, {})
        self.counts[layer][kind] = self.counts[layer].get(kind, 0) + 1

    def _extend(self, layer, points):
        b = self.box.setdefault(layer, [math.inf, math.inf, -math.inf, -math.inf])
        for x, y in points:
            b[0], b[1], b[2], b[3] = min(b[0], x), min(b[1], y), max(b[2], x), max(b[3], y)

    def line(self, layer, a, b):
        self.layer(layer)
        self.msp.add_line(a, b, dxfattribs={"layer": layer})
        self._count(layer, "LINE")
        self._extend(layer, [a, b])

    def stray_line(self, layer, a, b):
        self.layer(layer)
        self.msp.add_line(a, b, dxfattribs={"layer": layer})
        self.stray += 1  # read as stray: neither in the counts nor in the extents

    def quarter_arc(self, layer, center, radius, start_deg):
        """A door swing: 90 degrees counter-clockwise from start_deg (a multiple of 90)."""
        self.layer(layer)
        self.msp.add_arc(center, radius, start_deg, start_deg + 90, dxfattribs={"layer": layer})
        self._count(layer, "ARC")
        cx, cy = center
        a0, a1 = math.radians(start_deg), math.radians(start_deg + 90)
        self._extend(layer, [(cx, cy), (cx + radius * math.cos(a0), cy + radius * math.sin(a0)),
                             (cx + radius * math.cos(a1), cy + radius * math.sin(a1))])

    def rectangle_lwpolyline(self, layer, x0, y0, x1, y1):
        self.layer(layer)
        self.msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                                dxfattribs={"layer": layer})
        self._count(layer, "LWPOLYLINE")
        self._extend(layer, [(x0, y0), (x1, y1)])

    def rectangle_polyline2d(self, layer, x0, y0, x1, y1):
        self.layer(layer)
        self.msp.add_polyline2d([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                                dxfattribs={"layer": layer})
        self._count(layer, "POLYLINE")
        self._extend(layer, [(x0, y0), (x1, y1)])

    def text(self, layer, text, at, height, expected=None):
        """TEXT; `expected` is its label in UTF-8 when it differs from `text` (escapes, %% codes)."""
        self.layer(layer)
        self.msp.add_text(text, dxfattribs={"layer": layer, "height": height, "insert": at})
        self._count(layer, "TEXT")
        self.labels.append(expected if expected is not None else text)

    def mtext(self, layer, raw, at, height, expected):
        self.layer(layer)
        self.msp.add_mtext(raw, dxfattribs={"layer": layer, "char_height": height, "insert": at})
        self._count(layer, "MTEXT")
        self.labels.append(expected)

    def extents_m(self, layers=None, mpu=MM):
        bs = [b for layer, b in self.box.items() if layers is None or layer in layers]
        b = [min(x[0] for x in bs), min(x[1] for x in bs), max(x[2] for x in bs), max(x[3] for x in bs)]
        return {"min": [b[0] * mpu, b[1] * mpu], "max": [b[2] * mpu, b[3] * mpu]}

    def save(self, fmt="asc", mpu=MM, replace=None, **expect):
        path = os.path.join(HERE, self.name + ".dxf")
        self.doc.saveas(path, fmt=fmt)
        if replace:  # names ezdxf will not write (xref-dependent "ARCH|A-WALL"), patched into the ASCII file
            with open(path, "rb") as f:
                data = f.read()
            for old, new in replace.items():
                assert data.count(old.encode()) >= 1, old
                data = data.replace(old.encode(), new.encode())
            with open(path, "wb") as f:
                f.write(data)
            fix = lambda s: replace.get(s, s)
            self.counts = {fix(k): v for k, v in self.counts.items()}
            for key in ("occluder_layers", "not_occluder_layers"):
                if key in expect:
                    expect[key] = [fix(x) for x in expect[key]]
        e = self.extents_m(mpu=mpu)
        out = {
            "file": self.name + ".dxf",
            "size_m": [e["max"][0] - e["min"][0], e["max"][1] - e["min"][1]],
            "size_tolerance_m": 0.01,
            "extents_dxf_m": e,
            "layers": sorted(self.counts),
            "labels": self.labels,
            "entities_by_layer": self.counts,
            "stray_entities": self.stray,
            # DxfImportOptions::recentre_beyond_m (10 km): re-centred when the bulk lies further out
            "recentred": math.hypot((e["min"][0] + e["max"][0]) / 2, (e["min"][1] + e["max"][1]) / 2) > 10000.0,
            "binary": fmt == "bin",
        }
        out.update(expect)
        with open(os.path.join(HERE, self.name + ".expected.json"), "w", encoding="utf-8") as f:
            json.dump(out, f, indent=1, ensure_ascii=False)
            f.write("\n")
        return out


def diameter(template):
    """%%c is AutoCAD's diameter symbol: U+2205 (AutoCAD's documented Unicode for it), U+2300 (the Unicode
    DIAMETER SIGN) or U+00D8 (ezdxf's plain text) are accepted spellings."""
    return [template.format(c) for c in ("\u2205", "\u2300", "\u00d8")]


def office(p, dx=0.0, dy=0.0, wall="A-WALL", door="A-DOOR", text_layer="A-ANNO", labels=None, t=200.0,
           unit=1.0):
    """A 12 000 x 8 000 mm office: double-line walls `t` thick, a partition at x = 6000, two 900 mm doors
    drawn as quarter ARCs with their leaves, two labels. Drawn in `unit` drawing units per millimetre,
    offset by (dx, dy) drawing units."""
    W, H, d = 12000.0, 8000.0, 900.0
    P = lambda x, y: (x * unit + dx, y * unit + dy)
    L = lambda a, b: p.line(wall, P(*a), P(*b))
    # south wall with the entrance between x = 2000 and 2900
    L((0, 0), (2000, 0)), L((2900, 0), (W, 0))
    L((t, t), (2000, t)), L((2900, t), (W - t, t))
    L((2000, 0), (2000, t)), L((2900, 0), (2900, t))
    # east, north, west
    L((W, 0), (W, H)), L((W - t, t), (W - t, H - t))
    L((W, H), (0, H)), L((W - t, H - t), (t, H - t))
    L((0, H), (0, 0)), L((t, H - t), (t, t))
    # partition at x = 6000 .. 6000 + t with a door between y = 3000 and 3900
    px = 6000.0
    L((px, t), (px, 3000)), L((px, 3900), (px, H - t))
    L((px + t, t), (px + t, 3000)), L((px + t, 3900), (px + t, H - t))
    L((px, 3000), (px + t, 3000)), L((px, 3900), (px + t, 3900))
    # doors: swing and open leaf
    p.quarter_arc(door, P(2000, t), d * unit, 0)
    p.line(door, P(2000, t), P(2000, t + d))
    p.quarter_arc(door, P(px + t, 3000), d * unit, 0)
    p.line(door, P(px + t, 3000), P(px + t + d, 3000))
    for (x, y), (text, expected) in zip([(2500, 4000), (8500, 4000)], labels or [("Office 1", None),
                                                                            ("Office 2", None)]):
        p.text(text_layer, text, P(x, y), 250 * unit, expected)


def main():
    written = []

    # Binary R2018 (AC1032): closed LWPOLYLINE walls (outer and inner faces), a door, a label.
    p = Plan("ez_binary_r2018", "R2018", insunits=4)
    p.rectangle_lwpolyline("A-WALL", 0, 0, 6000, 4000)
    p.rectangle_lwpolyline("A-WALL", 250, 250, 5750, 3750)
    p.quarter_arc("A-DOOR", (1000, 250), 900, 0)
    p.text("A-ANNO", "Meeting room", (2500, 2000), 250)
    written.append(p.save(fmt="bin", units="mm", units_source_any_of=["header"], version="AC1032",
                          occluder_layers=["A-WALL"], not_occluder_layers=["A-DOOR", "A-ANNO"]))

    # Binary R12 (AC1009): 2-D POLYLINE walls, a door, a label; R12 has no $INSUNITS: inferred from the
    # 250 mm walls and the 900 mm door.
    p = Plan("ez_binary_r12", "R12")
    p.rectangle_polyline2d("WALLS", 0, 0, 6000, 4000)
    p.rectangle_polyline2d("WALLS", 250, 250, 5750, 3750)
    p.quarter_arc("DOORS", (1000, 250), 900, 0)
    p.text("TEXT", "Kitchen", (2500, 2000), 250)
    written.append(p.save(fmt="bin", units="mm", units_source_any_of=["inferred", "assumed"], version="AC1009",
                          occluder_layers=["WALLS"], not_occluder_layers=["DOORS", "TEXT"]))

    # R2000 in code page 1252: German layer names and labels, %% codes, \U+ escapes, MTEXT formatting.
    p = Plan("ez_cp1252_r2000", "R2000", insunits=4, encoding="cp1252")
    office(p, wall="Wand (neu)", door="Türen", text_layer="Beschriftung",
           labels=[("Büro", None), ("Café Straße", None)])
    p.rectangle_lwpolyline("Möbel", 1000, 5000, 2600, 5800)
    p.text("Beschriftung", "Fläche 20 m² %%p 0,5", (1000, 1500), 200, "Fläche 20 m² ± 0,5")
    p.text("Beschriftung", "Drehung 90%%d, %%c 100", (1000, 1000), 200, diameter("Drehung 90°, {} 100"))
    p.text("Beschriftung", "Temperatur 20\\U+00B0C", (7000, 1000), 200, "Temperatur 20°C")
    p.mtext("Beschriftung", "{\\fArial|b0|i0|c0|p34;Besprechung}\\P{\\C1;rot} und \\H2.5x;groß", (7000, 6000), 200,
            "Besprechung\nrot und groß")
    p.mtext("Beschriftung", "%%c 80\\P%%p 0,5\\P90%%d", (7000, 7000), 200, diameter("{} 80\n± 0,5\n90°"))
    written.append(p.save(units="mm", units_source_any_of=["header"], version="AC1015", codepage="ANSI_1252",
                          occluder_layers=["Wand (neu)"], not_occluder_layers=["Türen", "Beschriftung", "Möbel"]))

    # R2000 in code page 936 (GBK): Chinese layer names (墙 wall, 门 door, 文字 text) and labels.
    p = Plan("ez_cp936_r2000", "R2000", insunits=4, encoding="gbk")
    office(p, wall="墙", door="门", text_layer="文字", labels=[("会议室", None), ("办公室", None)])
    written.append(p.save(units="mm", units_source_any_of=["header"], version="AC1015", codepage="ANSI_936",
                          occluder_layers=["墙"], not_occluder_layers=["门", "文字"]))

    # Solid HATCH walls (polyline boundary paths and an edge path) and columns (SOLID squares, a HATCH
    # circle): no line walls at all. 15 000 x 9 000 mm.
    p = Plan("ez_hatch_walls", "R2018", insunits=4)
    p.layer("A-WALL-PATT")
    p.layer("S-COLS")

    def wall_hatch(x0, y0, x1, y1, edges=False):
        h = p.msp.add_hatch(color=7, dxfattribs={"layer": "A-WALL-PATT"})
        h.set_solid_fill()
        corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        if edges:
            path = h.paths.add_edge_path()
            for a, b in zip(corners, corners[1:] + corners[:1]):
                path.add_line(a, b)
        else:
            h.paths.add_polyline_path(corners, is_closed=True)
        p._count("A-WALL-PATT", "HATCH")
        p._extend("A-WALL-PATT", [(x0, y0), (x1, y1)])

    W, H, t = 15000.0, 9000.0, 300.0
    wall_hatch(0, 0, W, t)
    wall_hatch(0, H - t, W, H, edges=True)
    wall_hatch(0, t, t, H - t)
    wall_hatch(W - t, t, W, H - t)
    for x in (5000, 10000):  # square columns as SOLID (third and fourth vertex in "Z" order)
        p.msp.add_solid([(x, 4300), (x + 400, 4300), (x, 4700), (x + 400, 4700)], dxfattribs={"layer": "S-COLS"})
        p._count("S-COLS", "SOLID")
        p._extend("S-COLS", [(x, 4300), (x + 400, 4700)])
    h = p.msp.add_hatch(color=7, dxfattribs={"layer": "S-COLS"})  # a round column, 500 mm across
    h.set_solid_fill()
    h.paths.add_edge_path().add_arc((7500, 2000), 250, 0, 360)
    p._count("S-COLS", "HATCH")
    p._extend("S-COLS", [(7250, 1750), (7750, 2250)])
    p.text("A-ANNO", "Hall", (7000, 6000), 300)
    written.append(p.save(units="mm", units_source_any_of=["header"], version="AC1032",
                          occluder_layers=["A-WALL-PATT", "S-COLS"], not_occluder_layers=["A-ANNO"]))

    # Unitless ($INSUNITS 0) office in millimetres: units inferred from the 900 mm door swings and the 200 mm
    # double-line walls.
    p = Plan("ez_unitless_mm", "R2000", insunits=0)
    office(p)
    written.append(p.save(units="mm", units_source_any_of=["inferred"], version="AC1015",
                          occluder_layers=["A-WALL"], not_occluder_layers=["A-DOOR", "A-ANNO"]))

    # The header says inches ($INSUNITS 1) but the office is drawn in millimetres (a 900-inch door is 23 m):
    # the contradiction case.
    p = Plan("ez_inch_header_mm", "R2000", insunits=1)
    office(p)
    written.append(p.save(units="mm", units_source_any_of=["inferred"], version="AC1015",
                          occluder_layers=["A-WALL"], not_occluder_layers=["A-DOOR", "A-ANNO"]))

    # Georeferenced style: the office at (2 500 000, 5 600 000) mm, and one stray LINE 1e7 units away
    # (6.1 km out: within the 10 km the importer computes in place, so not re-centred).
    p = Plan("ez_far_origin", "R2000", insunits=4)
    office(p, dx=2500000.0, dy=5600000.0)
    p.stray_line("A-ANNO", (12500000.0, 5600000.0), (12501000.0, 5600000.0))
    written.append(p.save(units="mm", units_source_any_of=["header"], version="AC1015",
                          occluder_layers=["A-WALL"], not_occluder_layers=["A-DOOR"]))

    # The same in metres at projected coordinates (E 2 500 000 m, N 5 600 000 m, as a UTM/Gauss-Krueger
    # export writes them), a stray LINE 1e7 m away: re-centred, the offset kept.
    p = Plan("ez_far_origin_m", "R2000", insunits=6)
    office(p, dx=2500000.0, dy=5600000.0, unit=MM)
    p.stray_line("A-ANNO", (12500000.0, 5600000.0), (12500001.0, 5600000.0))
    written.append(p.save(mpu=1.0, units="m", units_source_any_of=["header"], version="AC1015",
                          occluder_layers=["A-WALL"], not_occluder_layers=["A-DOOR"]))

    # Xref-bound layer names: "ARCH$0$A-WALL" (bound) and "ARCH|A-WALL" (xref-dependent, as AutoCAD writes it).
    p = Plan("ez_xref_layers", "R2000", insunits=4)
    office(p, wall="ARCH$0$A-WALL", door="ARCH$0$A-DOOR", text_layer="ARCH$0$A-ANNO")
    for x in (0.0, 12000.0):  # a second building block drawn on the xref-dependent layer
        p.line("ARCHxrefBARA-WALL", (x, 9000), (x, 12000))
    p.line("ARCHxrefBARA-WALL", (0, 12000), (12000, 12000))
    p.line("ARCHxrefBARA-WALL", (200, 9000), (200, 11800))
    p.line("ARCHxrefBARA-WALL", (11800, 9000), (11800, 11800))
    p.line("ARCHxrefBARA-WALL", (200, 11800), (11800, 11800))
    p.rectangle_lwpolyline("ARCHxrefBARA-FURN", 1000, 10000, 2600, 10800)
    written.append(p.save(units="mm", units_source_any_of=["header"], version="AC1015",
                          replace={"ARCHxrefBARA-WALL": "ARCH|A-WALL", "ARCHxrefBARA-FURN": "ARCH|A-FURN"},
                          occluder_layers=["ARCH$0$A-WALL", "ARCHxrefBARA-WALL"],
                          not_occluder_layers=["ARCH$0$A-DOOR", "ARCH$0$A-ANNO", "ARCHxrefBARA-FURN"]))

    # Walls on layer "0", doors on "1", labels on "2": no name says which block sight; geometry must
    # (parallel line pairs 0.2 m apart).
    p = Plan("ez_layer0_walls", "R2000", insunits=4)
    office(p, wall="0", door="1", text_layer="2")
    written.append(p.save(units="mm", units_source_any_of=["header"], version="AC1015",
                          occluder_layers=["0"], not_occluder_layers=["1", "2"]))

    # MLINE walls: a closed 240 mm MLINE (style WALL240, elements at +-120, justification zero) around a
    # 10 000 x 7 000 mm outline, and an open MLINE partition.
    p = Plan("ez_mline_walls", "R2018", insunits=4)
    style = p.doc.mline_styles.new("WALL240")
    style.elements.append(120.0)
    style.elements.append(-120.0)
    p.layer("A-WALL")
    W, H, h = 10000.0, 7000.0, 120.0
    m = p.msp.add_mline([(h, h), (W - h, h), (W - h, H - h), (h, H - h)], close=True,
                        dxfattribs={"layer": "A-WALL", "style_name": "WALL240", "scale_factor": 1.0,
                                    "justification": 1})
    assert m.style.dxf.name == "WALL240"
    p._count("A-WALL", "MLINE")
    p._extend("A-WALL", [(0, 0), (W, H)])
    p.msp.add_mline([(5000, h), (5000, H - h)],
                    dxfattribs={"layer": "A-WALL", "style_name": "WALL240", "scale_factor": 1.0,
                                "justification": 1})
    p._count("A-WALL", "MLINE")
    p.quarter_arc("A-DOOR", (5120, 3000), 900, 0)
    written.append(p.save(units="mm", units_source_any_of=["header"], version="AC1032",
                          occluder_layers=["A-WALL"], not_occluder_layers=["A-DOOR"]))

    # Nested INSERT arrays with a mirrored insert: DESK (1600 x 800 table, chair circle r 250 at (800, -400)),
    # ROW = three DESKs 2000 apart; model space: a 3 x 2 MINSERT of ROW and a mirrored ROW (x scale -1).
    p = Plan("ez_nested_inserts", "R2000", insunits=4)
    W, H, t = 20000.0, 12000.0, 200.0
    for a, b in [((0, 0), (W, 0)), ((W, 0), (W, H)), ((W, H), (0, H)), ((0, H), (0, 0)),
                 ((t, t), (W - t, t)), ((W - t, t), (W - t, H - t)), ((W - t, H - t), (t, H - t)),
                 ((t, H - t), (t, t))]:
        p.line("A-WALL", a, b)
    p.layer("A-FURN")
    desk = p.doc.blocks.new("DESK")
    desk.add_lwpolyline([(0, 0), (1600, 0), (1600, 800), (0, 800)], close=True, dxfattribs={"layer": "0"})
    desk.add_circle((800, -400), 250, dxfattribs={"layer": "0"})
    row = p.doc.blocks.new("ROW")
    for i in range(3):
        row.add_blockref("DESK", (2000 * i, 0), dxfattribs={"layer": "0"})
    # ROW's own box: x 0 .. 5600, y -650 .. 800
    ins = p.msp.add_blockref("ROW", (1000, 1000), dxfattribs={"layer": "A-FURN"})
    ins.grid(size=(3, 2), spacing=(2500, 6000))  # rows at y = 1000, 3500, 6000; columns at x = 1000, 7000
    p._count("A-FURN", "INSERT")
    p._extend("A-FURN", [(1000, 1000 - 650), (7000 + 5600, 6000 + 800)])
    p.msp.add_blockref("ROW", (19000, 9500), dxfattribs={"layer": "A-FURN", "xscale": -1.0})
    p._count("A-FURN", "INSERT")
    p._extend("A-FURN", [(19000 - 5600, 9500 - 650), (19000, 9500 + 800)])
    out = p.save(units="mm", units_source_any_of=["header"], version="AC1015",
                 occluder_layers=["A-WALL"], not_occluder_layers=["A-FURN"])
    out["layer_extents_dxf_m"] = {"A-FURN": p.extents_m(layers=["A-FURN"])}
    with open(os.path.join(HERE, p.name + ".expected.json"), "w", encoding="utf-8") as f:
        json.dump(out, f, indent=1, ensure_ascii=False)
        f.write("\n")
    written.append(out)

    for w in written:
        print(w["file"], "size", w["size_m"], "layers", w["layers"])


if __name__ == "__main__":
    main()
