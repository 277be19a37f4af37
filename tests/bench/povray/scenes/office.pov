// Office floor, 20 m x 12 m, 2.8 m high (plan coordinates, metres; see camera.inc for the axis mapping).
// A corridor (y 5..7) runs east-west; offices N1 N2 N3 to the north (open doors) and S1 S2 S3 to the south
// (S1 and S2 closed, separated by a 0.9 m thick service wall at x = 8; S3 open). Plain painted corridor,
// wallpapered N2, brick and wood panelling in places, carpet in the rooms, vinyl tiles in the corridor,
// ceiling tiles, point lights. The office walk uses the corridor and N2; the gap walk goes from S1 through
// the service wall into S2.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 4 }
#include "camera.inc"
#include "building.inc"
#declare WallH = 2.8;

// ---- walls (the DXF plan is read from these calls) ----
#declare WallTexture = texture { pigment { rgb <0.78, 0.76, 0.7> } finish { diffuse 0.75 } }
Wall(0, 0, 20, 0, 0.25)
Wall(20, 0, 20, 12, 0.25)
Wall(20, 12, 0, 12, 0.25)
Wall(0, 12, 0, 0, 0.25)
#declare WallTexture = texture { pigment { rgb <0.86, 0.84, 0.78> } finish { diffuse 0.8 } }  // corridor paint
Wall(0, 5, 2.925, 5, 0.15)
Wall(4.075, 5, 9.925, 5, 0.15)
Wall(11.075, 5, 15.925, 5, 0.15)
Wall(17.075, 5, 20, 5, 0.15)
Wall(0, 7, 1.925, 7, 0.15)
Wall(3.075, 7, 8.425, 7, 0.15)
Wall(9.575, 7, 14.925, 7, 0.15)
Wall(16.075, 7, 20, 7, 0.15)
Lintel(2.925, 5, 4.075, 5, 0.15, 2.1)
Lintel(9.925, 5, 11.075, 5, 0.15, 2.1)
Lintel(15.925, 5, 17.075, 5, 0.15, 2.1)
Lintel(1.925, 7, 3.075, 7, 0.15, 2.1)
Lintel(8.425, 7, 9.575, 7, 0.15, 2.1)
Lintel(14.925, 7, 16.075, 7, 0.15, 2.1)
#declare WallTexture = texture {  // N2 wallpaper
  pigment { bozo color_map { [0 rgb <0.75, 0.7, 0.55>] [0.5 rgb <0.85, 0.8, 0.65>] [1 rgb <0.6, 0.55, 0.45>] }
    scale 0.08 }
  finish { diffuse 0.8 } }
Wall(6, 7, 6, 12, 0.15)
Wall(12, 7, 12, 12, 0.15)
#declare WallTexture = texture {  // service wall between S1 and S2: brick
  pigment { brick rgb 0.75, rgb <0.55, 0.25, 0.18> brick_size <0.25, 0.075, 0.125> mortar 0.01 }
  finish { diffuse 0.8 } }
// A camera inside this wall (the gap walk) sees a uniform black: nothing to connect the two rooms by.
#declare WallInterior = texture { pigment { rgb 0 } finish { ambient 0 diffuse 0 } }
Wall(8, 0.58, 8, 4.47, 0.9)  // y 0.13..4.92: 5 mm short of the walls it meets, so none shows inside it
#undef WallInterior
#declare WallTexture = texture { pigment { rgb <0.7, 0.8, 0.75> } finish { diffuse 0.8 } }  // S3 paint
Wall(14, 0, 14, 5, 0.15)

// ---- doors ----
DoorLeaf(3.0, 5.0, 1.0, 0)       // S1, closed
DoorLeaf(10.0, 5.0, 1.0, 0)      // S2, closed
DoorLeaf(16.0, 4.925, 1.0, -75)  // S3, open
DoorLeaf(2.0, 7.075, 1.0, 80)    // N1
DoorLeaf(9.5, 7.075, 1.0, 105)   // N2
DoorLeaf(15.0, 7.075, 1.0, 60)   // N3

// ---- floors and ceiling ----
// floor and ceiling are cut out where the service wall stands, so that from inside it only black is seen
plane { y, 0 texture { pigment { granite color_map { [0 rgb <0.35, 0.36, 0.42>] [1 rgb <0.25, 0.26, 0.3>] } scale 0.3 } } clipped_by { box { P(7.549, 0.129, -1), P(8.451, 4.921, 4) inverse } } }
box { P(0, 5, -0.01), P(20, 7, 0.001) texture { pigment { checker rgb <0.7, 0.68, 0.6>, rgb <0.6, 0.58, 0.52> scale 0.5 } finish { specular 0.2 } } }
plane { y, WallH hollow texture { pigment { brick rgb 0.6, rgb 0.93 brick_size <0.6, 0.6, 0.6> mortar 0.015 } finish { diffuse 0.8 } } clipped_by { box { P(7.549, 0.129, -1), P(8.451, 4.921, 4) inverse } } }

// ---- corridor furniture ----
Picture(5.0, 6.925, -90, 0.8, 0.6, 1.5, pigment { agate scale 0.4 })
Picture(13.0, 5.075, 90, 1.0, 0.7, 1.5, pigment { marble turbulence 0.8 color_map { [0 rgb <0.2, 0.3, 0.6>] [1 rgb <0.9, 0.8, 0.3>] } scale 0.3 })
Picture(19.875, 6.0, 180, 1.2, 0.8, 1.5, pigment { spiral1 5 color_map { [0 rgb 0.2] [0.5 rgb <0.8, 0.2, 0.1>] [1 rgb 0.9] } scale 0.3 })
Plant(0.5, 5.5, 11)
Plant(19.4, 6.6, 12)
box { P(6.5, 5.08, 0.3), P(8.0, 5.35, 0.9) pigment { rgb <0.3, 0.35, 0.45> } }  // cabinet
box { P(18.5, 6.7, 0.0), P(19.0, 6.92, 0.8) pigment { rgb <0.8, 0.1, 0.1> } }  // fire hose box

// ---- N2: open-plan office (the office walk loops here) ----
Desk(7.3, 11.4, 180, rgb <0.7, 0.6, 0.45>)
Chair(7.3, 10.8, 0, rgb <0.1, 0.2, 0.5>)
Desk(10.6, 11.4, 180, rgb <0.9, 0.9, 0.9>)
Chair(10.4, 10.7, 20, rgb <0.5, 0.1, 0.1>)
Desk(11.5, 8.3, 90, rgb <0.7, 0.6, 0.45>)
Chair(10.9, 8.1, -70, rgb <0.1, 0.4, 0.2>)
Shelf(6.3, 9.5, 90, 3)
Shelf(6.3, 10.55, 90, 4)
Plant(11.6, 7.5, 13)
Picture(9.0, 11.875, -90, 1.4, 0.9, 1.6, pigment { leopard turbulence 0.3 color_map { [0 rgb <0.9, 0.7, 0.2>] [1 rgb <0.2, 0.1, 0.05>] } scale 0.05 })
Picture(11.925, 10.0, 180, 0.7, 0.9, 1.5, pigment { wood turbulence 0.3 color_map { [0 rgb <0.2, 0.5, 0.3>] [1 rgb <0.9, 0.9, 0.7>] } scale 0.1 })
box { P(6.075, 7.8, 0.9), P(6.1, 9.0, 2.0) pigment { rgb 0.97 } finish { specular 0.3 } }  // whiteboard

// ---- N1, N3: seen through the open doors ----
Desk(3.0, 11.3, 180, rgb <0.5, 0.4, 0.3>)
Shelf(0.3, 9.0, 90, 5)
Picture(3.0, 7.075, 90, 1.0, 0.6, 1.5, pigment { crackle color_map { [0 rgb <0.1, 0.1, 0.3>] [1 rgb <0.9, 0.5, 0.2>] } scale 0.1 })
Desk(16.0, 11.3, 180, rgb <0.8, 0.8, 0.8>)
Shelf(19.7, 9.5, -90, 6)
Plant(13.0, 11.5, 14)
#declare WallTexture = texture { pigment { wood turbulence 0.05 color_map { [0 rgb <0.6, 0.4, 0.22>] [1 rgb <0.45, 0.3, 0.15>] } scale <0.04, 0.04, 1> rotate 90 * x } }
box { P(12.08, 8.0, 0), P(12.12, 11.5, 1.2) texture { WallTexture } }  // N3 wainscot

// ---- S3: meeting room ----
box { P(15.5, 1.5, 0.72), P(18.5, 3.0, 0.76) pigment { rgb <0.4, 0.25, 0.15> } }
cylinder { P(16.2, 2.25, 0), P(16.2, 2.25, 0.72), 0.06 pigment { rgb 0.3 } }
cylinder { P(17.8, 2.25, 0), P(17.8, 2.25, 0.72), 0.06 pigment { rgb 0.3 } }
Chair(16.0, 1.1, 90, rgb <0.2, 0.2, 0.2>)
Chair(17.0, 1.1, 90, rgb <0.2, 0.2, 0.2>)
Chair(18.0, 3.4, -90, rgb <0.2, 0.2, 0.2>)
box { P(19.85, 1.0, 0.9), P(19.875, 3.5, 2.0) pigment { rgb 0.97 } }

// ---- S1: closed office (gap walk, first piece) ----
Desk(1.2, 4.3, 0, rgb <0.6, 0.5, 0.35>)
Chair(1.3, 3.7, 180, rgb <0.6, 0.4, 0.1>)
Desk(5.5, 0.7, 180, rgb <0.9, 0.9, 0.85>)
Chair(5.3, 1.3, 10, rgb <0.1, 0.3, 0.6>)
Shelf(0.3, 1.6, 90, 7)
Shelf(7.3, 4.2, -90, 8)
Plant(7.2, 0.5, 15)
Picture(3.5, 0.125, 90, 1.6, 1.0, 1.6, pigment { bozo turbulence 0.5 color_map { [0 rgb <0.1, 0.4, 0.1>] [0.5 rgb <0.8, 0.8, 0.2>] [1 rgb <0.1, 0.1, 0.5>] } scale 0.15 })
Picture(4.5, 4.925, -90, 0.9, 0.7, 1.5, pigment { hexagon rgb <0.8, 0.2, 0.2>, rgb <0.2, 0.2, 0.8>, rgb 0.9 scale 0.08 rotate 90 * x })

// ---- S2: closed store/office (gap walk, second piece) ----
Shelf(9.0, 0.3, 0, 21)
Shelf(10.05, 0.3, 0, 22)
Shelf(11.1, 0.3, 0, 23)
Desk(11.0, 4.5, 0, rgb <0.3, 0.3, 0.3>)
Chair(10.3, 4.3, 200, rgb <0.8, 0.2, 0.1>)
box { P(8.6, 3.5, 0), P(9.4, 4.8, 1.1) pigment { rgb <0.45, 0.5, 0.55> } finish { specular 0.4 } }  // cabinet
Plant(13.6, 0.5, 24)
Picture(11.5, 4.925, -90, 1.2, 0.8, 1.6, pigment { onion turbulence 0.4 color_map { [0 rgb <0.9, 0.3, 0.1>] [1 rgb <0.1, 0.6, 0.7>] } scale 0.2 })
Picture(13.925, 2.0, 180, 0.8, 1.0, 1.5, pigment { gradient y color_map { [0 rgb <0.1, 0.1, 0.2>] [0.5 rgb <0.9, 0.9, 0.4>] [1 rgb <0.1, 0.1, 0.2>] } turbulence 0.6 scale 0.3 })

// ---- lights ----
#declare Lamp = rgb 0.55;
#macro CeilLamp(X, Y, C)
  CeilLampS(X, Y, C, off)
#end
#macro CeilLampS(X, Y, C, Shadowless)  // Shadowless: cheaper, for lamps that light mostly one room
  light_source { P(X, Y, WallH - 0.15), C fade_distance 2.5 fade_power 2 #if (Shadowless) shadowless #end
    looks_like { box { <-0.3, 0.1, -0.3>, <0.3, 0.14, 0.3> pigment { rgb 1 } finish { ambient 1 diffuse 0 } } } }
#end
#declare InS12 = (CamLz < 5.0 & CamLx < 14);
#if (InS12)
  CeilLamp(2.5, 2.5, Lamp) CeilLamp(6.0, 2.5, Lamp)
  CeilLamp(10.0, 2.0, Lamp * <1, 0.95, 0.85>) CeilLamp(12.5, 3.5, Lamp * <1, 0.95, 0.85>)
#else
  CeilLamp(3.0, 6.0, Lamp) CeilLamp(10.0, 6.0, Lamp) CeilLamp(17.0, 6.0, Lamp)
  CeilLamp(7.8, 9.5, Lamp) CeilLamp(10.5, 10.0, Lamp)
  CeilLampS(3.0, 9.5, Lamp, on) CeilLampS(16.0, 9.5, Lamp, on) CeilLampS(17.0, 2.5, Lamp, on)
#end
