#pragma once
// The author's scene as the depth passes must see it (povray_render.h): the distance is coded by a fog of
// the studio's own, so a fog, media or radiosity of the author's would mix into it (a ground fog 8 m thick
// puts walls 20 m away several metres off). For the depth passes the scene's files are read through a copy
// in which those are neutralised; the colour pass renders the scene as the author wrote it.
#include <string>

namespace plenopath {

// The SDL text with every `fog { ... }` made one too thin to see (distance 1e12: 1e-11 of the coding at
// 10 m), every `media { ... }` made empty (it adds nothing) and every `radiosity { ... }` removed (its
// gathering rays see the studio's fog). Comments and strings are left as they are, and so is a block that
// does not close (POV-Ray reports it). `changed` (optional) gets the number of blocks changed.
std::string without_atmosphere(const std::string& sdl, int* changed = nullptr);

// The scene file and the other .pov and .inc files of its folder (not its subfolders) copied into
// `copy_dir` without their atmosphere. POV-Ray, run in `copy_dir` with the scene's folder as its library
// path, then reads the copies first and everything else (image maps, includes in subfolders) from the
// author's folder. Returns the copied scene file's path and the blocks changed in all files. Throws Error
// when a file cannot be read or written.
struct AtmosphereFreeScene {
  std::string scene_file;
  int blocks_changed = 0;
};
AtmosphereFreeScene copy_scene_without_atmosphere(const std::string& scene_file, const std::string& copy_dir);

}  // namespace plenopath
