# Optional and extra dependencies, included by CMakeLists.txt once HAMLIE_LINK
# is set.  PLplot (cairo devices) draws the figures in src/report/plot.c.
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)
target_link_libraries(hamlie_obj PUBLIC PkgConfig::PLPLOT)
list(APPEND HAMLIE_LINK PkgConfig::PLPLOT)

# libgccjit (Debian: libgccjit-12-dev) compiles tapes to machine code in
# process (src/tape/jit.c, hl_tape_jit).  Optional: without it hl_tape_jit
# reports HL_EUNSUP and the interpreter runs; -DHAMLIE_GCCJIT=OFF builds
# without it even where it is installed.
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
  target_link_libraries(hamlie_obj PUBLIC ${GCCJIT_LIB})
  list(APPEND HAMLIE_LINK ${GCCJIT_LIB})
else()
  message(STATUS "libgccjit: not used (hl_tape_jit reports HL_EUNSUP)")
endif()
