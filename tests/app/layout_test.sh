#!/usr/bin/env bash
# The source layout ARCHITECTURE.md describes (issue 17): processing/ in subsystem folders, each mirrored by a
# test folder; heavy libraries only in the few files that need them. Usage: layout_test.sh CLI DATA SOURCE_DIR
set -uo pipefail
src=${3:?source dir}
cd "$src" || exit 2
fail=0
bad() { echo "layout: $*" >&2; fail=1; }

# No loose sources at the top of processing/: every file belongs to a subsystem.
for f in processing/*.cpp processing/*.h; do [[ -e $f ]] && bad "$f is not in a subsystem folder"; done
# Every subsystem has its test folder (tests mirror the source tree), and no test folder is orphaned.
for d in processing/*/; do
  d=${d%/}; name=${d#processing/}
  [[ -d tests/processing/$name ]] || bad "processing/$name has no tests/processing/$name"
done
for d in tests/processing/*/; do
  d=${d%/}; name=${d#tests/processing/}
  [[ -d processing/$name ]] || bad "tests/processing/$name mirrors no processing/$name"
done
# Heavy headers stay in the translation units that need them.
while IFS= read -r f; do
  [[ $f == *_cgal.cpp ]] || bad "$f includes CGAL but is not a *_cgal.cpp file"
done < <(grep -rl '#include <CGAL/' processing model rig app widgets)
while IFS= read -r f; do
  # pose_graph_costs.h: the autodiff cost templates the anchor and plan refinements share, included only by
  # their .cpp files.
  case $f in processing/egomotion/*.cpp | processing/anchors/*.cpp | processing/stills/*.cpp | \
    processing/registration/*.cpp | processing/anchors/pose_graph_costs.h) ;;
  *) bad "$f includes Ceres outside egomotion/, anchors/, stills/ and registration/ .cpp files" ;; esac
done < <(grep -rl '#include <ceres/' processing model rig app widgets)
# Qt and VTK never below widgets/.
grep -rlE '#include <(Q[A-Za-z]+|vtk[A-Za-z]+\.h)>' processing model rig && bad "Qt or VTK included below widgets/"
# Each subsystem links only what it uses: CGAL and Ceres are private to their libraries.
grep -q 'plenopath_processing_library(hotspots PUBLIC plenopath_model plenopath_rig)' processing/CMakeLists.txt ||
  bad "processing/CMakeLists.txt: hotspots should link only model and rig"
# The pipeline layer (issue 17) is in the umbrella both faces link, and knows nothing of the faces.
tr '\n' ' ' < processing/CMakeLists.txt |
  grep -qE 'target_link_libraries\(plenopath_processing INTERFACE[^)]*plenopath_pipeline' ||
  bad "processing/CMakeLists.txt: plenopath_processing should link plenopath_pipeline"
grep -rlE '#include "(app|widgets)/' processing model rig && bad "processing, model or rig include app/ or widgets/"
[[ $fail -eq 0 ]] && echo "layout: ok"
exit $fail
