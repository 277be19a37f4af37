cmake_minimum_required(VERSION 3.20)
# cmake -DFILES="a.js|b.js|..." -DOUTPUT=out.js -P JoinFiles.cmake
# Concatenates FILES ('|'-separated, in that order) into OUTPUT, each preceded by a line naming it; OUTPUT is
# rewritten only when its content changes. The web player's modules (resources/player/src/) become the one
# player.js that is embedded and shipped: no bundler, the order is the list's.
string(REPLACE "|" ";" _files "${FILES}")
set(_out "")
foreach(_f IN LISTS _files)
  if(NOT EXISTS "${_f}")
    message(FATAL_ERROR "JoinFiles: ${_f} does not exist")
  endif()
  get_filename_component(_name "${_f}" NAME)
  file(READ "${_f}" _text)
  string(APPEND _out "// ==== ${_name}\n${_text}")
  if(NOT _text MATCHES "\n$")
    string(APPEND _out "\n")
  endif()
endforeach()
file(WRITE "${OUTPUT}.tmp" "${_out}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
