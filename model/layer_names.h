#pragma once
// What a CAD layer's name says about whether its lines block sight, in the naming conventions people use:
// AIA/NCS (A-WALL, S-COLS, A-DOOR, A-GLAZ), ISO 13567 (agent, element code, presentation), common English,
// German, French, Spanish, Italian, Dutch, Chinese and Japanese names; xref-bound names ("xref$0$A-WALL",
// "xref|A-WALL") are judged by their own part.
#include <string>

namespace plenopath {

// +1: the name says it blocks sight (walls, columns, structure); -1: it says it does not (doors, windows,
// glazing, furniture, text, dimensions, hatch patterns, grids, annotation); 0: the name says nothing.
// `reason`, when given, gets a short phrase ("AIA wall layer", "German 'Wand'").
int occluder_vote_from_name(const std::string& layer_name, std::string* reason = nullptr);

// Whether the name speaks of walls, columns or structure at all, even where other words outvote them
// ("A-WALL-PATT", "Wandschraffur", "A-21----H-"): a solid fill on such a layer is the wall itself.
bool name_mentions_occluder(const std::string& layer_name);

}  // namespace plenopath
