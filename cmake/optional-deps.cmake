# Optional and extra dependencies, included by CMakeLists.txt once HAMLIE_LINK
# is set.  PLplot (cairo devices) draws the figures in src/report/plot.c.
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)
target_link_libraries(hamlie_obj PUBLIC PkgConfig::PLPLOT)
list(APPEND HAMLIE_LINK PkgConfig::PLPLOT)
