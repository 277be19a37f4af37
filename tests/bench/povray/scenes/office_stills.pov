// The office floor (office.pov) shot as tripod stills (issue 20): the building unchanged, plus the tripod
// under the camera in every still (tripod.inc).
#include "office.pov"
#include "tripod.inc"
