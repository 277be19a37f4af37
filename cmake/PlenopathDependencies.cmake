# Every dependency comes from Debian 12 (cmake/install-deps.sh installs them).

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs videoio video features2d calib3d photo objdetect)
find_package(CGAL REQUIRED)
find_package(Ceres REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Threads REQUIRED)

list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
find_package(EXPAT REQUIRED)
# Tour packages as .zip, streamed entry by entry with ZIP64 (processing/export/package_writer).
find_package(LibArchive 3.3 REQUIRED)

find_package(PkgConfig REQUIRED)
pkg_check_modules(DXFLIB REQUIRED IMPORTED_TARGET dxflib)
# Video through FFmpeg's own libraries: frame-exact seeking and real time stamps (processing/capture).
pkg_check_modules(LIBAV REQUIRED IMPORTED_TARGET libavformat libavcodec libswscale libavutil)
# Still panoramas' EXIF and GPano XMP (processing/capture/photo_metadata).
pkg_check_modules(EXIV2 REQUIRED IMPORTED_TARGET exiv2)

if(PLENOPATH_BUILD_STUDIO)
  find_package(Qt5 5.15 REQUIRED COMPONENTS Core Gui Widgets OpenGL Test Concurrent)
  # VTK 9.1 on Debian needs MPI's C target declared first.
  find_package(MPI COMPONENTS C)
  find_package(VTK 9.1 REQUIRED COMPONENTS
    GUISupportQt RenderingOpenGL2 RenderingCore RenderingAnnotation RenderingFreeType
    InteractionStyle InteractionWidgets FiltersCore FiltersSources CommonCore CommonDataModel
    IOImage)
endif()

if(PLENOPATH_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(PLENOPATH_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
