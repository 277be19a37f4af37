# Compiler settings shared by every project target (never applied to third-party code).

find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_C_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
endif()

add_library(plenopath_warnings INTERFACE)
target_compile_options(plenopath_warnings INTERFACE -Wall -Wextra -Wpedantic -Werror)

if(PLENOPATH_SANITIZE)
  string(REPLACE "," ";" _sanitizers "${PLENOPATH_SANITIZE}")
  foreach(_s IN LISTS _sanitizers)
    add_compile_options(-fsanitize=${_s})
    add_link_options(-fsanitize=${_s})
  endforeach()
  add_compile_options(-fno-omit-frame-pointer -fno-sanitize-recover=all)
endif()

# plenopath_add_library(NAME DIR) globs the folder's sources so new files need no CMake edit.
function(plenopath_glob_sources out_var dir)
  file(GLOB_RECURSE _sources CONFIGURE_DEPENDS ${dir}/*.cpp)
  set(${out_var} ${_sources} PARENT_SCOPE)
endfunction()

# CGAL translation units stay at -O2 even in Debug: -O0 makes visibility queries several times slower.
function(plenopath_optimize_cgal_sources)
  foreach(_f IN LISTS ARGN)
    set_source_files_properties(${_f} PROPERTIES COMPILE_OPTIONS "-O2")
  endforeach()
endfunction()
