# Test helpers shared by every test folder.
#
# fsi_add_gtest(TARGET t SOURCES a.cpp ... LIBS l ... LABELS unit ...)
#   one GoogleTest executable registered as one CTest test (serial).
# fsi_add_mpi_test(NAME n RANKS r COMMAND exe args... LABELS mpi ...)
#   runs COMMAND under mpiexec with RANKS ranks (oversubscribed, loopback only).
# fsi_add_test_folders([SKIP name ...])
#   add_subdirectory() for every sub-folder of the calling folder that has a
#   CMakeLists.txt (tests/<layer>/, tests/cases/<case>/), except the SKIP names.
# FSI_MPIEXEC / FSI_MPI_FLAGS / FSI_MPI_ENV are exported for tests that build
# their own launch lines (MPMD, two mpiruns + ompi-server).

set(FSI_MPIEXEC ${MPIEXEC_EXECUTABLE})
set(FSI_MPI_FLAGS --oversubscribe --allow-run-as-root --mca btl self,vader,tcp)
set(FSI_MPI_ENV
    OMPI_MCA_btl_tcp_if_include=lo
    OMPI_MCA_oob_tcp_if_include=lo
    OMPI_ALLOW_RUN_AS_ROOT=1
    OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    OMPI_MCA_rmaps_base_oversubscribe=1)

function(fsi_add_gtest)
  cmake_parse_arguments(A "" "TARGET" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${A_TARGET} ${A_SOURCES})
  target_link_libraries(${A_TARGET} PRIVATE ${A_LIBS} GTest::gtest_main fsi_warnings)
  set_target_properties(${A_TARGET} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  add_test(NAME ${A_TARGET} COMMAND ${A_TARGET} --gtest_color=no)
  set_tests_properties(${A_TARGET} PROPERTIES LABELS "${A_LABELS}" ENVIRONMENT "${FSI_MPI_ENV}")
endfunction()

function(fsi_add_mpi_test)
  cmake_parse_arguments(A "" "NAME;RANKS;TIMEOUT" "COMMAND;LABELS" ${ARGN})
  if(NOT A_TIMEOUT)
    set(A_TIMEOUT 120)
  endif()
  add_test(NAME ${A_NAME}
           COMMAND ${FSI_MPIEXEC} ${FSI_MPI_FLAGS} -np ${A_RANKS} ${A_COMMAND})
  set_tests_properties(${A_NAME} PROPERTIES LABELS "${A_LABELS}" PROCESSORS ${A_RANKS}
                       TIMEOUT ${A_TIMEOUT} ENVIRONMENT "${FSI_MPI_ENV}")
endfunction()

function(fsi_add_test_folders)
  cmake_parse_arguments(A "" "" "SKIP" ${ARGN})
  file(GLOB _dirs LIST_DIRECTORIES true ${CMAKE_CURRENT_SOURCE_DIR}/*)
  foreach(_dir ${_dirs})
    get_filename_component(_name ${_dir} NAME)
    if(IS_DIRECTORY ${_dir} AND EXISTS ${_dir}/CMakeLists.txt AND NOT _name IN_LIST A_SKIP)
      add_subdirectory(${_dir})
    endif()
  endforeach()
endfunction()
