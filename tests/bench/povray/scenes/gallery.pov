// Gallery hall, 26 m x 16 m, 7 m high (plan coordinates, metres; axis mapping in camera.inc). Two rows of
// round columns (y = 5 and y = 11), five tall windows in the south wall with the sun coming through them
// onto a glossy floor of polished stone tiles, two ceiling area lights, beams, paintings, plinths with
// sculptures and benches. Outside: a sunlit paved ground and the sky.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 3 }
#include "camera.inc"
#include "building.inc"
#declare WallH = 7.0;

#declare WallTexture = texture {
  pigment { bozo color_map { [0 rgb <0.88, 0.85, 0.8>] [1 rgb <0.82, 0.79, 0.74>] } scale 0.6 }
  finish { diffuse 0.75 } }
// south wall with five window openings (clear x 3-5, 8-10, 13-15, 18-20, 23-25)
Wall(0, 0, 2.8, 0, 0.4)
Wall(5.2, 0, 7.8, 0, 0.4)
Wall(10.2, 0, 12.8, 0, 0.4)
Wall(15.2, 0, 17.8, 0, 0.4)
Wall(20.2, 0, 22.8, 0, 0.4)
Wall(25.2, 0, 26, 0, 0.4)
Wall(26, 0, 26, 16, 0.4)
Wall(26, 16, 0, 16, 0.4)
Wall(0, 16, 0, 0, 0.4)
#for (K, 0, 4)
  #local X0 = 3 + 5 * K;
  box { P(X0, -0.2, 0), P(X0 + 2, 0.2, 0.6) texture { WallTexture } }                 // sill
  box { P(X0, -0.2, 5.5), P(X0 + 2, 0.2, WallH) texture { WallTexture } }             // lintel
  box { P(X0 + 0.97, -0.05, 0.6), P(X0 + 1.03, 0.05, 5.5) pigment { rgb 0.15 } }    // mullion
  box { P(X0, -0.05, 2.97), P(X0 + 2, 0.05, 3.03) pigment { rgb 0.15 } }             // transom
#end

#declare ColumnTexture = texture { pigment { marble turbulence 0.6 color_map { [0 rgb 0.92] [0.8 rgb 0.85] [1 rgb 0.55] } scale 0.4 }
  finish { specular 0.3 roughness 0.02 } }
Column(4.5, 5, 0.35)
Column(9, 5, 0.35)
Column(13.5, 5, 0.35)
Column(18, 5, 0.35)
Column(22.5, 5, 0.35)
Column(4.5, 11, 0.35)
Column(9, 11, 0.35)
Column(13.5, 11, 0.35)
Column(18, 11, 0.35)
Column(22.5, 11, 0.35)
// column bases and capitals
#for (K, 0, 4)
  #for (J, 0, 1)
    #local X = 4.5 + 4.5 * K; #local Y = 5 + 6 * J;
    box { P(X - 0.45, Y - 0.45, 0), P(X + 0.45, Y + 0.45, 0.3) texture { ColumnTexture } }
    box { P(X - 0.45, Y - 0.45, WallH - 0.5), P(X + 0.45, Y + 0.45, WallH) texture { ColumnTexture } }
  #end
#end
// beams across the hall over the columns
#for (K, 0, 4)
  box { P(4.3 + 4.5 * K, 0, WallH - 0.5), P(4.7 + 4.5 * K, 16, WallH) pigment { rgb 0.8 } }
#end

// glossy floor: polished stone tiles 1 m, inside the hall only
#declare StoneA = texture { pigment { granite color_map { [0 rgb <0.55, 0.5, 0.45>] [1 rgb <0.35, 0.3, 0.28>] } scale 0.4 }
  finish { reflection 0.15 specular 0.6 roughness 0.005 } }
#declare StoneB = texture { pigment { marble turbulence 0.8 color_map { [0 rgb <0.85, 0.83, 0.78>] [1 rgb <0.6, 0.58, 0.55>] } scale 0.5 }
  finish { reflection 0.15 specular 0.6 roughness 0.005 } }
box { P(0, 0, -0.1), P(26, 16, 0.0) texture { checker texture { StoneA } texture { StoneB } scale 1.0 } }
plane { y, -0.02 texture { pigment { brick rgb 0.45, rgb <0.7, 0.65, 0.55> brick_size <0.6, 0.2, 0.3> mortar 0.02 } } }
box { P(-0.5, -0.5, WallH), P(26.5, 16.5, WallH + 0.4) texture { pigment { rgb 0.85 } finish { diffuse 0.8 } } }  // roof (a plane would shade the sun)
sky_sphere { pigment { gradient y color_map { [0 rgb <0.85, 0.9, 1.0>] [0.4 rgb <0.4, 0.55, 0.9>] [1 rgb <0.2, 0.35, 0.8>] } } }
box { P(-10, -40, 0), P(40, -25, 12) pigment { brick rgb 0.6, rgb <0.6, 0.35, 0.25> brick_size <0.8, 0.3, 0.4> scale 1 } }  // building across the street

// paintings (north, east, west walls) and sculptures
Picture(3.5, 15.8, -90, 2.0, 1.4, 2.2, pigment { agate color_map { [0 rgb <0.7, 0.2, 0.1>] [0.5 rgb <0.9, 0.8, 0.4>] [1 rgb <0.1, 0.1, 0.3>] } scale 0.5 })
Picture(8.0, 15.8, -90, 2.4, 1.6, 2.3, pigment { leopard turbulence 0.5 color_map { [0 rgb <0.1, 0.3, 0.5>] [1 rgb <0.9, 0.9, 0.8>] } scale 0.12 })
Picture(12.5, 15.8, -90, 1.6, 2.0, 2.3, pigment { spiral2 6 turbulence 0.3 color_map { [0 rgb <0.8, 0.6, 0.1>] [1 rgb <0.2, 0.1, 0.1>] } scale 0.6 })
Picture(17.0, 15.8, -90, 2.8, 1.8, 2.4, pigment { crackle turbulence 0.2 color_map { [0 rgb <0.1, 0.4, 0.2>] [0.1 rgb <0.9, 0.9, 0.2>] [1 rgb <0.2, 0.6, 0.8>] } scale 0.3 })
Picture(22.0, 15.8, -90, 1.8, 1.2, 2.2, pigment { wood turbulence 0.6 color_map { [0 rgb <0.6, 0.1, 0.3>] [1 rgb <0.95, 0.8, 0.7>] } scale 0.3 })
Picture(25.8, 8.0, 180, 3.0, 2.0, 2.5, pigment { granite color_map { [0 rgb <0.1, 0.1, 0.1>] [0.5 rgb <0.8, 0.3, 0.2>] [1 rgb <0.9, 0.9, 0.9>] } scale 0.8 })
Picture(25.8, 13.0, 180, 1.4, 1.8, 2.2, pigment { onion turbulence 0.5 color_map { [0 rgb <0.2, 0.2, 0.6>] [1 rgb <0.9, 0.6, 0.3>] } scale 0.4 })
Picture(0.2, 8.0, 0, 2.2, 1.5, 2.3, pigment { hexagon rgb <0.7, 0.1, 0.1>, rgb <0.1, 0.5, 0.7>, rgb 0.9 scale 0.15 rotate 90 * x })
Picture(0.2, 12.5, 0, 1.5, 1.5, 2.2, pigment { marble turbulence 1.2 color_map { [0 rgb <0.2, 0.5, 0.2>] [1 rgb <0.95, 0.95, 0.6>] } scale 0.5 })
#macro Plinth(X, Y, Obj)
  box { P(X - 0.3, Y - 0.3, 0), P(X + 0.3, Y + 0.3, 1.0) pigment { rgb 0.95 } }
  object { Obj translate P(X, Y, 1.0) }
#end
Plinth(11.0, 9.6, sphere { <0, 0.35, 0>, 0.35 pigment { rgb <0.7, 0.45, 0.2> } finish { metallic specular 0.8 reflection 0.2 } })
Plinth(12.0, 14.0, torus { 0.3, 0.08 rotate 90 * x translate <0, 0.4, 0> pigment { rgb <0.2, 0.2, 0.25> } finish { specular 0.6 } })
Plinth(20.5, 9.0, cone { <0, 0, 0>, 0.25, <0, 0.9, 0>, 0.0 pigment { rgb <0.8, 0.1, 0.1> } })
Plinth(5.5, 13.8, box { <-0.2, 0, -0.2>, <0.2, 0.6, 0.2> rotate 30 * y pigment { rgb <0.1, 0.4, 0.6> } })
#macro Bench(X, Y, A)
  union { box { <-1, 0.42, -0.22>, <1, 0.47, 0.22> pigment { rgb <0.45, 0.3, 0.18> } }
    box { <-0.9, 0, -0.18>, <-0.85, 0.42, 0.18> } box { <0.85, 0, -0.18>, <0.9, 0.42, 0.18> }
    pigment { rgb 0.2 } Place(X, Y, A) }
#end
Bench(11.25, 6.4, 0) Bench(20.25, 6.4, 0) Bench(6.75, 12.1, 0) Bench(24.5, 13.5, 90)

// light: the sun through the south windows, two ceiling area lights, a little fill
light_source { P(13, -45, 40), rgb <1.7, 1.55, 1.35> parallel point_at P(13, 8, 0) }
light_source { P(8, 8, 6.6), rgb 0.55 area_light <3, 0, 0>, <0, 0, 3>, 2, 2 adaptive 0 fade_distance 5 fade_power 2
  looks_like { box { <-1.5, 0, -1.5>, <1.5, 0.05, 1.5> pigment { rgb 1 } finish { ambient 1 diffuse 0 } } } }
light_source { P(18, 8, 6.6), rgb 0.55 area_light <3, 0, 0>, <0, 0, 3>, 2, 2 adaptive 0 fade_distance 5 fade_power 2
  looks_like { box { <-1.5, 0, -1.5>, <1.5, 0.05, 1.5> pigment { rgb 1 } finish { ambient 1 diffuse 0 } } } }
light_source { P(13, 8, 30), rgb 0.12 shadowless }
