# hamlie-mpi.so (src/cli/mpi_plugin.c): `hamlie sweep` across the ranks of
# an MPI job.  A module beside hamlie-cli.so, loaded by sweep_mpi.c only
# under mpirun (or with --mpi): no other command loads libmpi.  Skipped
# when MPI is absent (Debian: libopenmpi-dev openmpi-bin); `mpirun hamlie
# sweep` then says the plugin is missing.
find_package(MPI COMPONENTS C QUIET)
find_package(Threads REQUIRED)
if(MPI_C_FOUND)
  message(STATUS "MPI: ${MPI_C_LIBRARIES} (hamlie-mpi.so; ${MPIEXEC_EXECUTABLE})")
  add_library(hamlie_mpi_plugin MODULE ${PROJECT_SOURCE_DIR}/src/cli/mpi_plugin.c)
  set_target_properties(hamlie_mpi_plugin PROPERTIES PREFIX "" OUTPUT_NAME hamlie-mpi)
  target_include_directories(hamlie_mpi_plugin PRIVATE ${PROJECT_SOURCE_DIR}/src
                             ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(hamlie_mpi_plugin PRIVATE MPI::MPI_C Threads::Threads)
  add_dependencies(hamlie_cli hamlie_mpi_plugin) # beside the launcher, as hamlie-cli.so
  install(TARGETS hamlie_mpi_plugin LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/hamlie)

  # mpirun refuses root unless told (containers), and one machine has fewer
  # cores than ranks; set on the command, since a sanitizer build replaces
  # the tests' ENVIRONMENT (CMakeLists.txt).  Open MPI's own leaks there
  # come from components it has unloaded (no module to suppress by name).
  set(_mpirun ${CMAKE_COMMAND} -E env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
      OMPI_MCA_rmaps_base_oversubscribe=1)
  if(HAMLIE_SANITIZE)
    list(APPEND _mpirun ASAN_OPTIONS=detect_leaks=0)
  endif()
  list(APPEND _mpirun ${MPIEXEC_EXECUTABLE})
  # the protocol with a fake sweep, on 1, 2 and 4 ranks (oversubscribed);
  # the test loads the plugin as sweep_mpi.c does
  add_executable(mpi-t-protocol ${PROJECT_SOURCE_DIR}/tests/mpi/t-protocol.c)
  target_include_directories(mpi-t-protocol PRIVATE ${PROJECT_SOURCE_DIR}/src
                             ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(mpi-t-protocol PRIVATE ${CMAKE_DL_LIBS} Threads::Threads)
  foreach(np 1 2 4)
    add_test(NAME mpi/protocol-np${np}
             COMMAND ${_mpirun} --oversubscribe ${MPIEXEC_NUMPROC_FLAG} ${np}
                     $<TARGET_FILE:mpi-t-protocol> $<TARGET_FILE:hamlie_mpi_plugin>)
  endforeach()
  # rank 0 stopping (an interrupt) and a rank running another sweep: the
  # master says so and ends the job (abort, with the test's own verdict)
  foreach(mode stop mismatch)
    add_test(NAME mpi/protocol-${mode}
             COMMAND ${_mpirun} --oversubscribe ${MPIEXEC_NUMPROC_FLAG} 3
                     $<TARGET_FILE:mpi-t-protocol> $<TARGET_FILE:hamlie_mpi_plugin> ${mode})
    set_tests_properties(mpi/protocol-${mode} PROPERTIES PASS_REGULAR_EXPRESSION "${mode}: (.* )?0 failures")
  endforeach()
  set(_mpi_tests mpi/protocol-np1 mpi/protocol-np2 mpi/protocol-np4 mpi/protocol-stop
      mpi/protocol-mismatch)
  # a deadlock fails the test instead of hanging CTest
  set_tests_properties(${_mpi_tests} PROPERTIES TIMEOUT 300)
else()
  message(STATUS "MPI: not found (hamlie-mpi.so not built; mpirun hamlie sweep will say so)")
  set(_mpi_tests)
endif()
if(TEST cli/mpi)
  list(APPEND _mpi_tests cli/mpi)
  set_tests_properties(cli/mpi PROPERTIES SKIP_RETURN_CODE 77)
endif()
if(_mpi_tests)
  # mpirun refuses root unless told; tests in containers often run as root
  set_property(TEST ${_mpi_tests} APPEND PROPERTY ENVIRONMENT
               OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1)
endif()
