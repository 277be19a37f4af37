// The office floor (office.pov) shot as tripod stills (issue 20): the building unchanged, plus the tripod
// under the camera in every still. The tripod is modelled in the camera's frame (CamMatrix, camera.inc), so
// it turns with the camera's heading like a real one: three legs from the head 0.15 m below the lens to the
// floor 0.45 m out, a centre column and a pan head 0.1 m below the lens. It fills the panorama below about
// -65 deg elevation.
#include "office.pov"

#declare TripodTexture = texture { pigment { rgb <0.08, 0.08, 0.09> } finish { specular 0.3 roughness 0.05 } }
#declare TripodHeight = CamLy;  // the lens above the floor (POV y is up)
union {
  #for (Leg, 0, 2)
    #local A = radians(90 + 120 * Leg);
    cylinder { <0, -0.15, 0>, <0.45 * cos(A), -TripodHeight, 0.45 * sin(A)>, 0.014 }
  #end
  // The pan head and the column stay below about -65 deg seen from the lens, as under a real 360 camera:
  // a head 2 cm under the lens (as this scene first had it) hid the whole floor below -22 deg.
  cylinder { <0, -0.14, 0>, <0, -0.55, 0>, 0.022 }  // centre column
  box { <-0.03, -0.14, -0.03>, <0.03, -0.10, 0.03> }  // pan head under the lens
  texture { TripodTexture }
  transform { CamMatrix }
}
