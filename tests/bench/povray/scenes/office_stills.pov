// The office floor (office.pov) shot as tripod stills (issue 20): the building unchanged, plus the tripod
// under the camera in every still. The tripod is modelled in the camera's frame (CamMatrix, camera.inc), so
// it turns with the camera's heading like a real one: three legs from the head 0.15 m below the lens to the
// floor 0.45 m out, a centre column and a pan head. It fills the panorama below about -70 deg elevation.
#include "office.pov"

#declare TripodTexture = texture { pigment { rgb <0.08, 0.08, 0.09> } finish { specular 0.3 roughness 0.05 } }
#declare TripodHeight = CamLy;  // the lens above the floor (POV y is up)
union {
  #for (Leg, 0, 2)
    #local A = radians(90 + 120 * Leg);
    cylinder { <0, -0.15, 0>, <0.45 * cos(A), -TripodHeight, 0.45 * sin(A)>, 0.014 }
  #end
  cylinder { <0, -0.05, 0>, <0, -0.55, 0>, 0.022 }  // centre column
  box { <-0.04, -0.05, -0.05>, <0.04, -0.02, 0.05> }  // pan head under the lens
  texture { TripodTexture }
  transform { CamMatrix }
}
