# The hamlie executable as a launcher plus a module (src/cli/launch.c says
# why): `hamlie --version` and `--help` load libc alone; a command loads
# hamlie-cli.so, the commands linked with the library (FLINT and all).
#   hamlie_cli          the launcher, output name `hamlie` (tests run it)
#   hamlie_cli_module   hamlie-cli.so: src/cli/*.c but the launcher's files
#   hamlie_launch_gen   build-time helper writing launch_table.c, the
#                       launcher's copy of main.c's texts
include(GNUInstallDirs)
file(GLOB CLI_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/cli/*.c)
set(LAUNCH_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/launch.c ${PROJECT_SOURCE_DIR}/src/cli/launch_gen.c)
list(REMOVE_ITEM CLI_SOURCES ${LAUNCH_SOURCES})
list(REMOVE_ITEM CLI_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/mpi_plugin.c) # hamlie-mpi.so's (mpi.cmake)
list(REMOVE_ITEM CLI_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/arb_lazy.c) # the module's alone (below)

add_library(hamlie_cli_obj OBJECT ${CLI_SOURCES})
target_link_libraries(hamlie_cli_obj PRIVATE hamlie_static) # its include paths

# Arb is loaded on first use (src/cli/arb_lazy.c says why): the module links
# the library's archive by its file, which brings no Arb with it, and the
# rest of the library's dependencies by name; -z defs makes an Arb call the
# forwarders lack a link error (not under the sanitizers: clang's runtime)
add_library(hamlie_cli_module MODULE $<TARGET_OBJECTS:hamlie_cli_obj>
            ${PROJECT_SOURCE_DIR}/src/cli/arb_lazy.c)
set_target_properties(hamlie_cli_module PROPERTIES PREFIX "" OUTPUT_NAME hamlie-cli)
target_include_directories(hamlie_cli_module PRIVATE
                           $<TARGET_PROPERTY:hamlie_static,INTERFACE_INCLUDE_DIRECTORIES>)
set(HAMLIE_LINK_LAZY_ARB ${HAMLIE_LINK})
list(REMOVE_ITEM HAMLIE_LINK_LAZY_ARB ${ARB_LIB})
target_link_libraries(hamlie_cli_module PRIVATE $<TARGET_FILE:hamlie_static> ${HAMLIE_LINK_LAZY_ARB})
add_dependencies(hamlie_cli_module hamlie_static)
set_property(TARGET hamlie_cli_module APPEND PROPERTY LINK_DEPENDS $<TARGET_FILE:hamlie_static>)
if(NOT HAMLIE_SANITIZE AND NOT HAMLIE_FUZZ)
  target_link_options(hamlie_cli_module PRIVATE -Wl,-z,defs)
endif()
get_filename_component(_arb_real ${ARB_LIB} REALPATH)
get_filename_component(_arb_file ${_arb_real} NAME)
string(REGEX REPLACE "(\\.so\\.[0-9]+).*$" "\\1" _arb_soname ${_arb_file})
set_property(SOURCE ${PROJECT_SOURCE_DIR}/src/cli/arb_lazy.c APPEND PROPERTY COMPILE_DEFINITIONS
             HAMLIE_ARB_SONAME="${_arb_soname}" HAMLIE_ARB_PATH="${_arb_real}")

add_executable(hamlie_launch_gen ${PROJECT_SOURCE_DIR}/src/cli/launch_gen.c
               $<TARGET_OBJECTS:hamlie_cli_obj>)
target_link_libraries(hamlie_launch_gen PRIVATE hamlie_static)
set(LAUNCH_TABLE ${PROJECT_BINARY_DIR}/launch_table.c)
add_custom_command(OUTPUT ${LAUNCH_TABLE}
  # a sanitizer build's leak check is no business of the build
  COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0
          $<TARGET_FILE:hamlie_launch_gen> ${LAUNCH_TABLE}
  DEPENDS hamlie_launch_gen
  COMMENT "Copying the command line's texts for the launcher")

# where the installed launcher finds the module: bin/ -> lib/hamlie/
file(RELATIVE_PATH HAMLIE_CLI_MODULE_DIR ${CMAKE_INSTALL_FULL_BINDIR}
     ${CMAKE_INSTALL_FULL_LIBDIR}/hamlie)
add_executable(hamlie_cli ${PROJECT_SOURCE_DIR}/src/cli/launch.c ${LAUNCH_TABLE})
set_target_properties(hamlie_cli PROPERTIES OUTPUT_NAME hamlie)
target_include_directories(hamlie_cli PRIVATE ${PROJECT_SOURCE_DIR}/src)
target_compile_definitions(hamlie_cli PRIVATE HAMLIE_CLI_MODULE_DIR="${HAMLIE_CLI_MODULE_DIR}")
target_link_libraries(hamlie_cli PRIVATE ${CMAKE_DL_LIBS})
add_dependencies(hamlie_cli hamlie_cli_module) # a command needs it beside the launcher

install(TARGETS hamlie_cli_module LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/hamlie)
