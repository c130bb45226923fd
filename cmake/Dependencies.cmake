# Every dependency comes from Debian; a missing one stops configuration and names the package.

function(vsil_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR "vsil needs ${what}: install the Debian package '${package}' "
                        "(apt-get install ${package}), or run scripts/bootstrap.sh")
  endif()
endfunction()

# A library Debian ships without a CMake config that works (or none): finds HEADER (in the
# PATH_SUFFIXES folders) and each of LIBRARIES, requires them all from `package`, and makes the
# INTERFACE target `target` carrying them, in that link order.
function(vsil_import_library target what package)
  cmake_parse_arguments(arg "" "HEADER" "PATH_SUFFIXES;LIBRARIES" ${ARGN})
  string(MAKE_C_IDENTIFIER "${target}" id)
  string(TOUPPER "${id}" id)
  find_path(${id}_INCLUDE_DIR ${arg_HEADER} PATH_SUFFIXES ${arg_PATH_SUFFIXES})
  vsil_require(${id}_INCLUDE_DIR "${what} headers" ${package})
  add_library(${target} INTERFACE IMPORTED)
  target_include_directories(${target} INTERFACE ${${id}_INCLUDE_DIR})
  foreach(library ${arg_LIBRARIES})
    find_library(${id}_${library}_LIBRARY ${library})
    vsil_require(${id}_${library}_LIBRARY "${what} (lib${library})" ${package})
    target_link_libraries(${target} INTERFACE ${${id}_${library}_LIBRARY})
  endforeach()
endfunction()

find_package(PkgConfig QUIET)

# OpenGL back ends (slicing/gl_context.h): OSMesa and headless EGL. Each is built when its
# headers are installed (VSIL_OSMESA / VSIL_EGL: AUTO builds it if present, ON requires it, OFF
# leaves it out); at least one is needed. Neither library is linked: slicing/gl_backends/ opens
# libOSMesa.so.8 or libEGL.so.1 with dlopen when a context is asked for, so one binary runs
# where either is installed (Mesa dropped OSMesa in 25.1) and says which is missing otherwise.
set(VSIL_OSMESA AUTO CACHE STRING "Build the OSMesa back end: AUTO (if libosmesa6-dev is there), ON, OFF")
set(VSIL_EGL AUTO CACHE STRING "Build the EGL back end: AUTO (if libegl-dev is there), ON, OFF")
set_property(CACHE VSIL_OSMESA PROPERTY STRINGS AUTO ON OFF)
set_property(CACHE VSIL_EGL PROPERTY STRINGS AUTO ON OFF)

find_path(GL_COREARB_INCLUDE_DIR GL/glcorearb.h)
vsil_require(GL_COREARB_INCLUDE_DIR "the OpenGL core-profile header GL/glcorearb.h" libgl-dev)
add_library(vsil::gl INTERFACE IMPORTED)
target_include_directories(vsil::gl INTERFACE ${GL_COREARB_INCLUDE_DIR})
target_link_libraries(vsil::gl INTERFACE ${CMAKE_DL_LIBS})

# Sets <option>_BUILT and adds the headers' folder to vsil::gl.
function(vsil_gl_backend option what package)
  set(built OFF)
  string(TOUPPER "${${option}}" mode)
  if(mode STREQUAL "AUTO" OR ${option})
    find_path(${option}_INCLUDE_DIR ${ARGN})
    if(${option}_INCLUDE_DIR)
      set(built ON)
      target_include_directories(vsil::gl INTERFACE ${${option}_INCLUDE_DIR})
    elseif(NOT mode STREQUAL "AUTO")
      vsil_require(${option}_INCLUDE_DIR "${what} (${option}=ON)" ${package})
    endif()
  endif()
  set(${option}_BUILT ${built} PARENT_SCOPE)
endfunction()
vsil_gl_backend(VSIL_OSMESA "the OSMesa headers" libosmesa6-dev GL/osmesa.h)
vsil_gl_backend(VSIL_EGL "the EGL headers" libegl-dev EGL/egl.h EGL/eglext.h)
if(NOT VSIL_OSMESA_BUILT AND NOT VSIL_EGL_BUILT)
  message(FATAL_ERROR "vsil needs an OpenGL back end: install the Debian package 'libegl-dev' "
                      "(EGL) or 'libosmesa6-dev' (OSMesa), or run scripts/bootstrap.sh")
endif()
message(STATUS "vsil GL back ends: osmesa ${VSIL_OSMESA_BUILT}, egl ${VSIL_EGL_BUILT}")

# FFTW (single precision, with its threads library): Gaussian broadening in postfx.
vsil_import_library(vsil::fftw "FFTW (single precision, threads)" libfftw3-dev HEADER fftw3.h
                    LIBRARIES fftw3f_threads fftw3f)

# OpenCV core/imgproc: images in memory, distance transforms. Debian's per-module -dev packages
# ship no CMake config, so the modules are found one by one. imgcodecs (image files) is linked
# into the tests only (vsil::opencv_imgcodecs): Debian's build pulls in GDAL and ~120 shared
# libraries with it, ~60 ms at every process start; vsil reads and writes PNG through libpng.
find_path(OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
vsil_require(OPENCV_INCLUDE_DIR "OpenCV headers" libopencv-core-dev)
add_library(vsil::opencv INTERFACE IMPORTED)
target_include_directories(vsil::opencv INTERFACE ${OPENCV_INCLUDE_DIR})
foreach(module core imgproc imgcodecs)
  find_library(OPENCV_${module}_LIBRARY opencv_${module})
  vsil_require(OPENCV_${module}_LIBRARY "OpenCV ${module}" libopencv-${module}-dev)
endforeach()
target_link_libraries(vsil::opencv INTERFACE ${OPENCV_core_LIBRARY} ${OPENCV_imgproc_LIBRARY})
add_library(vsil::opencv_imgcodecs INTERFACE IMPORTED)
target_link_libraries(vsil::opencv_imgcodecs INTERFACE vsil::opencv ${OPENCV_imgcodecs_LIBRARY})

# libpng: PNG files in and out (core/image_file.h).
find_package(PNG QUIET)
vsil_require(PNG_FOUND "libpng" libpng-dev)

# OpenCV videoio (with FFmpeg in Debian's build): `vsil animate --video`, and only there.
find_library(OPENCV_videoio_LIBRARY opencv_videoio)
vsil_require(OPENCV_videoio_LIBRARY "OpenCV videoio (vsil animate --video)" libopencv-videoio-dev)
add_library(vsil::opencv_videoio INTERFACE IMPORTED)
target_link_libraries(vsil::opencv_videoio INTERFACE vsil::opencv_imgcodecs ${OPENCV_videoio_LIBRARY})

find_package(glm QUIET)
find_path(GLM_INCLUDE_DIR glm/glm.hpp)
vsil_require(GLM_INCLUDE_DIR "GLM" libglm-dev)

find_package(nlohmann_json 3 QUIET)
vsil_require(nlohmann_json_FOUND "nlohmann JSON" nlohmann-json3-dev)

find_package(CLI11 QUIET)
vsil_require(CLI11_FOUND "CLI11 (command-line parsing)" libcli11-dev)

# cpp-httplib: the HTTP server of `vsil serve`. Debian builds it as a shared library
# (libcpp-httplib.so) with OpenSSL, zlib and Brotli support, and the header must be compiled
# with the same defines, which only its pkg-config file carries (no CMake config).
if(PkgConfig_FOUND)
  pkg_check_modules(CPP_HTTPLIB QUIET IMPORTED_TARGET cpp-httplib)
endif()
vsil_require(CPP_HTTPLIB_FOUND "cpp-httplib (vsil serve) and pkg-config" libcpp-httplib-dev)
add_library(vsil::httplib INTERFACE IMPORTED)
target_link_libraries(vsil::httplib INTERFACE PkgConfig::CPP_HTTPLIB)

find_package(tinyxml2 QUIET)
vsil_require(tinyxml2_FOUND "TinyXML-2 (VTK XML files)" libtinyxml2-dev)

find_package(ZLIB QUIET)
vsil_require(ZLIB_FOUND "zlib (compressed VTI, NRRD and MetaImage payloads)" zlib1g-dev)

# libdeflate: VTI's zlib blocks, inflated whole about 2.5 times as fast as by zlib.
vsil_import_library(vsil::deflate "libdeflate (VTI zlib blocks)" libdeflate-dev
                    HEADER libdeflate.h LIBRARIES deflate)
# VTI files written with vtkLZ4DataCompressor and vtkLZMADataCompressor.
vsil_import_library(vsil::lz4 "LZ4 (VTI files compressed with LZ4)" liblz4-dev HEADER lz4.h
                    LIBRARIES lz4)
find_package(LibLZMA QUIET)
vsil_require(LIBLZMA_FOUND "liblzma (VTI files compressed with LZMA)" liblzma-dev)
# NIfTI-1/-2 files. Debian's NIFTIConfig.cmake names the nifti tools, which libnifti2-dev does
# not install, so find_package(NIFTI) fails: vsil_import_library finds them directly.
vsil_import_library(vsil::nifti "nifticlib (NIfTI files)" libnifti2-dev HEADER nifti2_io.h
                    PATH_SUFFIXES nifti LIBRARIES nifti2 znz)
target_link_libraries(vsil::nifti INTERFACE ZLIB::ZLIB m)
# DICOM series (GDCM, with its codecs for compressed transfer syntaxes). Debian's
# GDCMConfig.cmake, like NIfTI's, fails without the command-line tools (libgdcm-tools).
vsil_import_library(vsil::gdcm "GDCM (DICOM series)" libgdcm-dev HEADER gdcmImageReader.h
                    PATH_SUFFIXES gdcm-3.0 LIBRARIES gdcmMSFF gdcmDSED gdcmDICT gdcmCommon)

find_package(Threads REQUIRED)

# MPI (Open MPI from Debian: libopenmpi-dev, openmpi-bin), optional: slab-parallel rendering
# under `mpirun` and `vsil sweep` (src/mpi). Without it vsil builds and renders as before, and
# what needs MPI says so in one line. -DVSIL_MPI=OFF builds without it even where it is found.
option(VSIL_MPI "Build MPI support (slab-parallel render, vsil sweep) where MPI is found" ON)
# CI's build 1 (.ci/run) sets it: a machine that lost Open MPI must fail there, not quietly
# build without it and skip the MPI tests.
option(VSIL_REQUIRE_MPI "Stop configuring when MPI is not found (needs VSIL_MPI)" OFF)
if(VSIL_REQUIRE_MPI AND NOT VSIL_MPI)
  message(FATAL_ERROR "-DVSIL_REQUIRE_MPI=ON contradicts -DVSIL_MPI=OFF")
endif()
set(VSIL_HAVE_MPI OFF)
if(VSIL_MPI)
  find_package(MPI QUIET COMPONENTS CXX)
  if(VSIL_REQUIRE_MPI)
    vsil_require(MPI_CXX_FOUND "MPI (Open MPI, -DVSIL_REQUIRE_MPI=ON)" libopenmpi-dev)
    vsil_require(MPIEXEC_EXECUTABLE "an MPI launcher (mpirun, -DVSIL_REQUIRE_MPI=ON)" openmpi-bin)
  endif()
  if(MPI_CXX_FOUND)
    set(VSIL_HAVE_MPI ON)
  else()
    message(STATUS "vsil: MPI not found (apt-get install libopenmpi-dev openmpi-bin): "
                   "building without slab-parallel rendering and vsil sweep")
  endif()
endif()

if(VSIL_BUILD_TESTS)
  find_package(GTest QUIET)
  vsil_require(GTest_FOUND "GoogleTest" libgtest-dev)
endif()
if(VSIL_BUILD_BENCH)
  find_package(benchmark QUIET)
  vsil_require(benchmark_FOUND "Google Benchmark" libbenchmark-dev)
endif()

# The Python module (src/python): pybind11 and the interpreter's headers; numpy and pytest only
# at test time (tests/python).
if(VSIL_PYTHON)
  # Debian's interpreter, for which python3-numpy and pybind11-dev are built, before any other
  # python3 on the PATH (pyenv); in an active virtual environment ($VIRTUAL_ENV) its own
  # interpreter (FindPython looks there first), so that `cmake --install` puts the package in
  # the venv's site-packages, not the system's. -DPython3_EXECUTABLE=... chooses another (setup.py
  # passes the interpreter running pip).
  if(NOT DEFINED Python3_EXECUTABLE AND NOT DEFINED ENV{VIRTUAL_ENV} AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "the Python the module is built for")
  endif()
  find_package(Python3 QUIET COMPONENTS Interpreter Development.Module)
  vsil_require(Python3_Development.Module_FOUND "the Python headers (VSIL_PYTHON=ON)" python3-dev)
  find_package(pybind11 CONFIG QUIET)
  vsil_require(pybind11_FOUND "pybind11 (VSIL_PYTHON=ON)" pybind11-dev)
endif()
