# Optional and extra dependencies, included by CMakeLists.txt once HAMLIE_LINK
# is set.  PLplot (cairo devices) draws the figures in src/report/plot.c.
# Its headers only: the library is loaded on the first drawing
# (src/report/plplot_api.c), so that commands that draw nothing never pay.
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)
target_include_directories(hamlie_obj PRIVATE ${PLPLOT_INCLUDE_DIRS})
list(APPEND HAMLIE_LINK ${CMAKE_DL_LIBS})

# libgccjit (Debian: libgccjit-12-dev) compiles tapes to machine code in
# process (src/tape/jit.c, hl_tape_jit).  Optional: without it hl_tape_jit
# reports HL_EUNSUP and the interpreter runs; -DHAMLIE_GCCJIT=OFF builds
# without it even where it is installed.  Its header is needed at build
# time; the library is not linked but loaded on the first compilation
# (src/tape/gccjit_api.c), and its absence at run time is the same
# HL_EUNSUP.
option(HAMLIE_GCCJIT "Compile tapes to machine code with libgccjit when it is found" ON)
if(HAMLIE_GCCJIT)
  set(_gccjit_dirs /usr/lib/gcc/x86_64-linux-gnu/12 /usr/lib/x86_64-linux-gnu)
  if(CMAKE_C_COMPILER_VERSION)
    string(REGEX MATCH "^[0-9]+" _gcc_major ${CMAKE_C_COMPILER_VERSION})
    list(PREPEND _gccjit_dirs /usr/lib/gcc/x86_64-linux-gnu/${_gcc_major})
  endif()
  find_path(GCCJIT_INCLUDE libgccjit.h HINTS ${_gccjit_dirs} PATH_SUFFIXES include)
  find_library(GCCJIT_LIB NAMES gccjit libgccjit.so.0 HINTS ${_gccjit_dirs})
endif()
if(HAMLIE_GCCJIT AND GCCJIT_INCLUDE AND GCCJIT_LIB)
  message(STATUS "libgccjit: ${GCCJIT_LIB} (tapes can be compiled to machine code)")
  target_compile_definitions(hamlie_obj PRIVATE HAMLIE_HAVE_GCCJIT)
  # SYSTEM: the directory also holds GCC's own stddef.h etc.; searched after ours
  target_include_directories(hamlie_obj SYSTEM AFTER PRIVATE ${GCCJIT_INCLUDE})
  # tried after the soname, for a libgccjit off the loader's path
  target_compile_definitions(hamlie_obj PRIVATE HAMLIE_GCCJIT_PATH="${GCCJIT_LIB}")
else()
  message(STATUS "libgccjit: not used (hl_tape_jit reports HL_EUNSUP)")
endif()

# HDF5 (Debian: libhdf5-dev) writes the result files of `section` and
# `sweep` (src/report/h5.c).  Its headers at build time; the library is not
# linked but loaded on the first HDF5 file written (src/report/hdf5_api.c):
# libhdf5 pulls in some 36 libraries every start-up would pay for.  The
# file found here is tried after the soname (libhdf5_serial.so.103).
pkg_check_modules(HDF5 REQUIRED hdf5)
target_include_directories(hamlie_obj SYSTEM PRIVATE ${HDF5_INCLUDE_DIRS})
find_library(HDF5_LIB NAMES hdf5_serial hdf5 HINTS ${HDF5_LIBRARY_DIRS})
if(HDF5_LIB)
  get_filename_component(HDF5_LIB_REAL ${HDF5_LIB} REALPATH)
  set_property(SOURCE ${PROJECT_SOURCE_DIR}/src/report/hdf5_api.c APPEND PROPERTY
               COMPILE_DEFINITIONS HAMLIE_HDF5_PATH="${HDF5_LIB_REAL}")
endif()
# the sweep's HDF5 file records the version that wrote it
set_property(SOURCE ${PROJECT_SOURCE_DIR}/src/sweep/sweep_h5.c APPEND PROPERTY
             COMPILE_DEFINITIONS HAMLIE_VERSION_TEXT="${PROJECT_VERSION}")
