// Convention check (check_convention.py): four coloured boxes 1 m wide, from 1.1 m to 2.1 m above the
// floor, 5 m from the camera at plan (0, 0): red east (+X), green north (+Y), blue west, yellow south.
#version 3.7;
global_settings { assumed_gamma 1.0 }
#include "camera.inc"
light_source { P(0, 0, 2.9) rgb 1 shadowless }
background { rgb 0 }
#declare Flat = finish { ambient 1 diffuse 0 }
box { P(4.9, -0.5, 1.1), P(5.1, 0.5, 2.1) pigment { rgb <1, 0, 0> } finish { Flat } }
box { P(-0.5, 4.9, 1.1), P(0.5, 5.1, 2.1) pigment { rgb <0, 1, 0> } finish { Flat } }
box { P(-5.1, -0.5, 1.1), P(-4.9, 0.5, 2.1) pigment { rgb <0, 0, 1> } finish { Flat } }
box { P(-0.5, -5.1, 1.1), P(0.5, -4.9, 2.1) pigment { rgb <1, 1, 0> } finish { Flat } }
