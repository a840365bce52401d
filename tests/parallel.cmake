# Tests that need several MPI ranks: one executable, run under mpirun.
file(GLOB PARALLEL_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/parallel/*.cpp)
add_executable(parallel_tests ${PARALLEL_SOURCES} main_mpi.cpp)
target_link_libraries(parallel_tests PRIVATE granflow_lib GTest::gtest)
find_program(MPIRUN NAMES mpirun mpiexec REQUIRED)
add_test(NAME parallel_tests_2_ranks
         COMMAND ${MPIRUN} -np 2 --oversubscribe $<TARGET_FILE:parallel_tests>)
set_tests_properties(parallel_tests_2_ranks PROPERTIES
  LABELS parallel TIMEOUT 1200
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
