// Corridor loop round an inner block: outer walls 32 m x 20 m, inner block 27.6 m x 15.6 m, corridor 2 m wide
// and 2.6 m high, centre line about 95 m round (plan coordinates, metres; axis mapping in camera.inc).
// Plain painted walls and ceiling, a grey vinyl floor, closed doors every few metres, sparse fittings
// (notice boards, extinguishers, radiators), ceiling light panels; two fire-door frames across the corridor
// that the trolley passes 0.2 m from; three people walking; the trolley (mast, base, handle) and the
// operator pushing it, modelled in the camera's frame so that they move rigidly with it.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 4 }
#include "camera.inc"
#include "building.inc"
#declare WallH = 2.6;

#declare Paint = texture { pigment { rgb <0.84, 0.82, 0.74> } finish { diffuse 0.8 } }
#declare WallTexture = Paint;
// outer walls
Wall(0, 0, 32, 0, 0.2)
Wall(32, 0, 32, 20, 0.2)
Wall(32, 20, 0, 20, 0.2)
Wall(0, 20, 0, 0, 0.2)
// inner block
Wall(2.2, 2.2, 29.8, 2.2, 0.2)
Wall(29.8, 2.2, 29.8, 17.8, 0.2)
Wall(29.8, 17.8, 2.2, 17.8, 0.2)
Wall(2.2, 17.8, 2.2, 2.2, 0.2)
// fire-door frames across the corridor (1 m clear; the walk passes 0.2 m from one jamb)
#declare WallTexture = texture { pigment { rgb <0.75, 0.74, 0.7> } finish { diffuse 0.8 specular 0.1 } }
Wall(16, 0.1, 16, 0.825, 0.15)
Wall(16, 1.975, 16, 2.1, 0.15)
Lintel(16, 0.825, 16, 1.975, 0.15, 2.1)
Wall(14, 19.175, 14, 19.9, 0.15)
Wall(14, 17.9, 14, 18.025, 0.15)
Lintel(14, 18.025, 14, 19.175, 0.15, 2.1)

// floor and ceiling
plane { y, 0 texture { pigment { granite color_map { [0 rgb <0.42, 0.42, 0.4>] [1 rgb <0.34, 0.34, 0.33>] } scale 0.5 }
  finish { specular 0.15 roughness 0.02 } } }
plane { y, WallH hollow texture { pigment { rgb 0.9 } finish { diffuse 0.8 } } }
// skirting boards along every wall face
#declare Skirt = texture { pigment { rgb 0.25 } }
#macro SkirtX(X0, X1, Y) box { P(X0, Y - 0.012, 0), P(X1, Y + 0.012, 0.1) texture { Skirt } } #end
#macro SkirtY(Y0, Y1, X) box { P(X - 0.012, Y0, 0), P(X + 0.012, Y1, 0.1) texture { Skirt } } #end
SkirtX(0.1, 31.9, 0.1) SkirtX(0.1, 31.9, 19.9) SkirtY(0.1, 19.9, 0.1) SkirtY(0.1, 19.9, 31.9)
SkirtX(2.1, 29.9, 2.1) SkirtX(2.1, 29.9, 17.9) SkirtY(2.1, 17.9, 2.1) SkirtY(2.1, 17.9, 29.9)

// closed doors on a wall face: hinge end X (along the wall direction A), on the face at Y
#macro FaceDoor(X, Y, A)
  union {
    DoorLeaf(0, 0, 0.9, 0)
    box { <-0.06, 0, -0.03>, <0, 2.1, 0.03> } box { <0.9, 0, -0.03>, <0.96, 2.1, 0.03> }
    box { <-0.06, 2.05, -0.03>, <0.96, 2.11, 0.03> }
    pigment { rgb 0.35 }
    Place(X, Y, A)
  }
#end
FaceDoor(7.0, 0.1, 0) FaceDoor(12.5, 2.1, 0) FaceDoor(22.0, 0.1, 0) FaceDoor(26.0, 2.1, 0)
FaceDoor(31.9, 6.0, 90) FaceDoor(29.9, 11.0, 90) FaceDoor(31.9, 15.0, 90)
FaceDoor(24.0, 19.9, 0) FaceDoor(18.0, 17.9, 0) FaceDoor(9.0, 19.9, 0) FaceDoor(5.0, 17.9, 0)
FaceDoor(0.1, 13.0, 90) FaceDoor(2.1, 8.0, 90) FaceDoor(0.1, 4.5, 90)

// sparse fittings
Picture(10.0, 0.1, 90, 0.6, 0.8, 1.5, pigment { rgb <0.3, 0.45, 0.7> })          // notice board
Picture(20.0, 2.1, -90, 0.9, 0.6, 1.5, pigment { bozo color_map { [0 rgb 0.95] [1 rgb 0.75] } scale 0.05 })
Picture(31.9, 10.0, 180, 0.8, 0.6, 1.5, pigment { rgb <0.8, 0.75, 0.4> })
Picture(11.0, 19.9, -90, 1.0, 0.7, 1.5, pigment { agate color_map { [0 rgb 0.9] [1 rgb <0.2, 0.4, 0.2>] } scale 0.3 })
Picture(0.1, 9.0, 0, 0.6, 0.8, 1.5, pigment { rgb <0.7, 0.3, 0.3> })
#macro Extinguisher(X, Y)
  union { cylinder { P(X, Y, 0.3), P(X, Y, 0.85), 0.08 } sphere { P(X, Y, 0.85), 0.08 }
    pigment { rgb <0.8, 0.05, 0.05> } finish { specular 0.5 } }
  box { P(X - 0.15, Y - 0.15, 1.6), P(X + 0.15, Y + 0.15, 1.8) pigment { rgb <0.1, 0.6, 0.2> } }
#end
Extinguisher(15.5, 0.2) Extinguisher(31.8, 3.0) Extinguisher(14.5, 19.8) Extinguisher(0.2, 17.0)
#macro Radiator(X0, X1, Y)
  #for (K, 0, int((X1 - X0) / 0.08))
    box { P(X0 + K * 0.08, Y - 0.05, 0.15), P(X0 + K * 0.08 + 0.05, Y + 0.05, 0.75) pigment { rgb 0.95 } }
  #end
#end
Radiator(3.0, 4.2, 0.15) Radiator(25.0, 26.2, 19.85)
box { P(29.85, 13.0, 0), P(29.6, 14.2, 1.0) pigment { rgb <0.3, 0.3, 0.35> } }  // cabinet, east leg
box { P(2.15, 14.0, 0.9), P(2.4, 14.6, 1.4) pigment { rgb <0.9, 0.9, 0.85> } }     // wall box, west leg

// ceiling light panels and lights (shadowless: the loop is lit everywhere at little cost)
#macro Panel(X, Y, Along)
  box { P(X - (Along ? 0.6 : 0.3), Y - (Along ? 0.3 : 0.6), WallH - 0.02), P(X + (Along ? 0.6 : 0.3), Y + (Along ? 0.3 : 0.6), WallH)
    pigment { rgb 1 } finish { ambient 1 diffuse 0 } no_shadow }
#end
#macro Lamp(X, Y, Along)
  Panel(X, Y, Along)
  light_source { P(X, Y, WallH - 0.1), rgb 0.5 fade_distance 3 fade_power 2 shadowless }
#end
#for (K, 0, 6) Lamp(3 + K * 4.3, 1.1, true) Lamp(4 + K * 4.3, 18.9, true) #end
#for (K, 0, 3) Lamp(30.9, 3.5 + K * 4.3, false) Lamp(1.1, 4 + K * 4.3, false) #end
light_source { P(16, 10, 30), rgb 0.15 shadowless }  // a little sky through nothing: fill

// three people walking (NoPeople=1: the same walk without them, the truth of a clean plate)
#ifndef (NoPeople)
Walker(17.0, 0.45, 28.5, 0.45, 1.3, 0, rgb <0.2, 0.3, 0.6>, rgb 0.15)
Walker(30.25, 4.0, 30.25, 16.0, 1.2, 3, rgb <0.7, 0.2, 0.2>, rgb <0.2, 0.2, 0.3>)
Walker(27.0, 19.55, 15.0, 19.55, 1.4, 10, rgb <0.9, 0.8, 0.3>, rgb <0.3, 0.25, 0.2>)
#end

// the trolley and its operator, in the camera frame (x right, y up, z forward; floor at y = -1.5);
// NoRig=1: without them (what the camera would see of the floor and walls behind them)
#ifndef (NoRig)
union {
  union {
    cylinder { <0, -0.15, 0>, <0, -1.33, 0>, 0.02 }                                       // mast
    box { <-0.17, -1.38, -0.32>, <0.17, -1.32, 0.22> }                                   // base
    cylinder { <-0.14, -1.32, -0.3>, <-0.14, -0.55, -0.42>, 0.014 }                     // handle
    cylinder { <0.14, -1.32, -0.3>, <0.14, -0.55, -0.42>, 0.014 }
    cylinder { <-0.2, -0.55, -0.42>, <0.2, -0.55, -0.42>, 0.018 }
    pigment { rgb 0.2 } finish { specular 0.4 metallic }
  }
  #for (K, 0, 3)
    cylinder { <(K < 2 ? -0.16 : 0.16), -1.44, (mod(K, 2) = 0 ? -0.28 : 0.18)>,
      <(K < 2 ? -0.12 : 0.12), -1.44, (mod(K, 2) = 0 ? -0.28 : 0.18)>, 0.055 pigment { rgb 0.05 } }
  #end
  box { <-0.12, -1.32, -0.25>, <0.12, -1.15, 0.05> pigment { rgb <0.1, 0.1, 0.4> } }      // battery box
  box { <-0.17, -0.6, -0.36>, <0.17, -0.58, -0.12> pigment { rgb 0.1 } }                  // laptop on a tray
  object { PersonBody(FrameTime * 0.9, rgb <0.25, 0.5, 0.3>, rgb <0.15, 0.15, 0.2>, rgb <0.8, 0.62, 0.5>)
    translate <0, -1.5, -0.78> }
  transform { CamMatrix }
}
#end
