# Compiler settings shared by every project target (never applied to third-party code).

find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_C_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
endif()

add_library(plenopath_warnings INTERFACE)
target_compile_options(plenopath_warnings INTERFACE -Wall -Wextra -Wpedantic -Werror)

# The libFuzzer build instruments every project library (coverage for libFuzzer, ASan + UBSan checks); the
# fuzz targets themselves add -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt).
if(PLENOPATH_BUILD_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fno-sanitize=vptr -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=1)
endif()

if(PLENOPATH_SANITIZE)
  string(REPLACE "," ";" _sanitizers "${PLENOPATH_SANITIZE}")
  foreach(_s IN LISTS _sanitizers)
    add_compile_options(-fsanitize=${_s})
    add_link_options(-fsanitize=${_s})
  endforeach()
  add_compile_options(-fno-omit-frame-pointer -fno-sanitize-recover=all)
  # GCC 12 reports false "may be used uninitialized" inside CGAL's headers when the sanitizers' checks are
  # inlined at -O2 (std::make_pair(Direction_2(), false) in Epic_converter.h); warnings only, not -Werror.
  target_compile_options(plenopath_warnings INTERFACE -Wno-error=maybe-uninitialized)
  # CGAL's arrangements static_cast their DCEL records to the Arrangement_2 wrapper types (Face, Halfedge,
  # ...), which UBSan's dynamic-type check reports in every arrangement iteration: benign and not ours.
  if("undefined" IN_LIST _sanitizers)
    add_compile_options(-fno-sanitize=vptr)
  endif()
  # Eigen turns its own aligned allocator on under ASan (EIGEN_MALLOC_ALREADY_ALIGNED 0) while Debian's
  # libceres was built without it: a matrix Ceres allocates and our code frees is then freed at the wrong
  # address. glibc's and ASan's malloc both align to 16 bytes, so keep Eigen on plain malloc everywhere.
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=1)
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
