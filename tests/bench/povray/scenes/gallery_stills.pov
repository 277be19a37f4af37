// The gallery hall (gallery.pov) shot as tripod stills (issue 20): one 26 x 16 m room, walls 8-13 m from
// most stills, two rows of marble columns, sun through the south windows; plus the tripod (tripod.inc).
#include "gallery.pov"
#include "tripod.inc"
