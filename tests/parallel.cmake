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

# A soil case on 2 ranks writing every output (fields, lines, history): the gathered fields exist on
# the root only, and the other rank must not touch them. The summary gives the ranks' peak memory.
add_test(NAME cli_run_soil_case_2_ranks_with_output
         COMMAND sh -c "d=$2; $0 -np 2 --oversubscribe \"$1\" run \"$3\" -o \"$d\" --overwrite --set 'mesh.cells=[60,20]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > \"$d.log\" 2>&1 || { cat \"$d.log\"; exit 1; }; test $(grep -c DataSet \"$d/fields.pvd\") -eq 3 && test $(wc -l < \"$d/history.csv\") -gt 2 && test -s \"$d/fields_00002.vtr\" && test -s \"$d/surface_00002.csv\" && test -s \"$d/checkpoint/fields.bin\" && grep -q '^peak memory [1-9][0-9]* MB .summed over 2 ranks.$' \"$d.log\""
                 ${MPIRUN} $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/soil_2_ranks ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_run_soil_case_2_ranks_with_output PROPERTIES
  LABELS parallel TIMEOUT 300
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# More ranks than the cells can be shared by: one message, no PETSc error trace.
add_test(NAME cli_too_many_ranks_for_the_cells
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 ${MPIRUN} -np 2 --oversubscribe $<TARGET_FILE:granflow> run ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml
                 -o ${CMAKE_CURRENT_BINARY_DIR}/too_many_ranks --overwrite --set "mesh.cells=[3,3]" --set time.end=0.01)
set_tests_properties(cli_too_many_ranks_for_the_cells PROPERTIES
  LABELS parallel TIMEOUT 120 PASS_REGULAR_EXPRESSION "error: [^\n]*lid_driven_cavity_re100.toml: mesh.cells: 3 x 3 cells cannot be shared by 2 ranks"
  FAIL_REGULAR_EXPRESSION "PETSC ERROR"
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# An output directory that cannot be made (here under a file) is one message from rank 0, status 2,
# not one per rank and an abort.
add_test(NAME cli_output_directory_cannot_be_made_2_ranks
         COMMAND sh -c "touch \"$2\"; out=$($0 -np 2 --oversubscribe \"$1\" run \"$3\" -o \"$2/sub\" --set 'mesh.cells=[8,8]' 2>&1); status=$?; echo \"$out\"; test $status -eq 2 && echo \"$out\" | head -1 | grep -q '^error: -o .*a_file/sub: cannot make the output directory: Not a directory' && ! echo \"$out\" | grep -qE 'MPI_ABORT|rank 1'"
                 ${MPIRUN} $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/a_file ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_output_directory_cannot_be_made_2_ranks PROPERTIES
  LABELS parallel TIMEOUT 120
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# Line samples on 2 ranks are those of 1 rank (the fields are gathered to the root before sampling),
# up to the solver tolerance; the profile through a soil layer included.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/compare_line_samples.py
"import sys\nimport numpy as np\na = np.genfromtxt(sys.argv[1], delimiter=',', skip_header=2)\nb = np.genfromtxt(sys.argv[2], delimiter=',', skip_header=2)\nassert a.shape == b.shape and a.shape[1] == 9, (a.shape, b.shape)\nd = np.abs(a - b).max(axis=0) / np.maximum(np.abs(a).max(axis=0), 1e-30)\nprint('largest relative difference per column:', ' '.join(f'{x:.1e}' for x in d))\nsys.exit(0 if d.max() < 1e-6 else 1)\n")
add_test(NAME cli_line_samples_2_ranks_as_1
         COMMAND sh -c "m=$0; g=$1; d=$2; c=$3; { cat \"$c\"; printf '[[output.line]]\\nname = \"profile\"\\nstart = [0.1, 0.0]\\nend = [0.1, 0.1]\\npoints = 41\\n'; } > \"$d.toml\" && for n in 1 2; do $m -np $n --oversubscribe \"$g\" run \"$d.toml\" -o \"$d$n\" --overwrite --set 'mesh.cells=[60,20]' --set time.end=0.05 --set output.fields=false --set output.progress_seconds=0 > /dev/null || exit 1; done; /usr/bin/python3 \"$4\" \"$d\"1/profile.csv \"$d\"2/profile.csv"
                 ${MPIRUN} $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/line_ranks ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${CMAKE_CURRENT_BINARY_DIR}/compare_line_samples.py)
set_tests_properties(cli_line_samples_2_ranks_as_1 PROPERTIES
  LABELS parallel TIMEOUT 300
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# `check` on two ranks says its verdict once.
add_test(NAME cli_check_2_ranks_says_once
         COMMAND sh -c "out=$(\"$0\" -np 2 --oversubscribe \"$1\" check \"$2\" 2>&1) || exit 1; test $(echo \"$out\" | grep -c 'valid (') -eq 1"
                 ${MPIRUN} $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_check_2_ranks_says_once PROPERTIES LABELS parallel
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")

# A command line refused before MPI starts is said once, not by every rank.
add_test(NAME cli_command_line_error_2_ranks_says_once
         COMMAND sh -c "out=$(\"$0\" -np 2 --oversubscribe \"$1\" frob 2>&1); test $? -eq 2 && test $(echo \"$out\" | grep -c '^error: unknown command') -eq 1 && out=$(\"$0\" -np 2 --oversubscribe \"$1\" run x.toml --bogus 2>&1); test $? -eq 2 && test $(echo \"$out\" | grep -c '^error: run does not take: --bogus (see granflow run --help)') -eq 1"
                 ${MPIRUN} $<TARGET_FILE:granflow>)
set_tests_properties(cli_command_line_error_2_ranks_says_once PROPERTIES LABELS parallel
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")

# A PETSc error every rank meets (out of memory while the grid is made: 16 million cells within 1.5 GB
# of address space a rank) is one line, from rank 0, and status 1 (README, "Exit status"), not one line
# per rank and PETSc's error code.
add_test(NAME cli_petsc_error_2_ranks_once
         COMMAND sh -c "out=$(ulimit -v 1500000; \"$0\" -np 2 --oversubscribe \"$1\" run \"$2\" -o \"$3\" --overwrite --set 'mesh.cells=[4000,4000]' --set time.end=0.01 2>&1); status=$?; echo \"$out\"; test $status -eq 1 && test $(echo \"$out\" | grep -c '^error: PETSc: out of memory') -eq 1 && ! echo \"$out\" | grep -q 'rank 1)'"
                 ${MPIRUN} $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/petsc_error_2_ranks)
set_tests_properties(cli_petsc_error_2_ranks_once PROPERTIES LABELS parallel TIMEOUT 120
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# The lithostatic floor's overburden sums each column over the ranks that share it (4 x 20 cells on
# 2 ranks are split across the columns).
add_test(NAME lithostatic_floor_2_ranks
         COMMAND ${MPIRUN} -np 2 --oversubscribe $<TARGET_FILE:verification_tests> --gtest_filter=LithostaticFloor.*)
set_tests_properties(lithostatic_floor_2_ranks PROPERTIES
  LABELS parallel TIMEOUT 120
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# The solver's advection of the soil fraction on 2 ranks (ghost exchange across the ranks' boundary)
# against the serial driver of the advection tests.
add_test(NAME production_advection_2_ranks
         COMMAND ${MPIRUN} -np 2 --oversubscribe $<TARGET_FILE:unit_tests> --gtest_filter=ProductionAdvection.*)
set_tests_properties(production_advection_2_ranks PROPERTIES
  LABELS parallel TIMEOUT 120
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# The 3D sweeps of the soil fraction on 2 ranks (a mesh of layers split along z, ghosts exchanged after
# each sweep) against the same on one rank, to the bit.
add_test(NAME vof_sweeps_3d_2_ranks
         COMMAND ${MPIRUN} -np 2 --oversubscribe $<TARGET_FILE:unit_tests> --gtest_filter=VofSweep3d.RanksSweepAsOneRank)
set_tests_properties(vof_sweeps_3d_2_ranks PROPERTIES
  LABELS parallel TIMEOUT 120
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# The flow solver and the soil phase on a mesh of layers split over 2 ranks: the layer-independent
# cavity and water column still give the planar runs (all on 2 ranks), flat layers split along the
# vertical stay at rest, and a granular column spreads as its axisymmetric twin; a column under the
# coupled solve with an air band, split across x or z (25 x 10 x 25 cells), moves as over the whole
# domain, momentum moved with its mass across the ranks' join; a collapse against a floor and two walls
# built of blocked cells moves as against the domain's own (the blocked cells mirrored across the join);
# periodic strips of layers are the planar runs (the water strip split along x, across its join), and
# a layer slides between frictional side walls as on one rank.
add_test(NAME flow_3d_2_ranks
         COMMAND ${MPIRUN} -np 2 --oversubscribe $<TARGET_FILE:verification_tests>
                 --gtest_filter=FlowSolver3d.ALayerIndependentCavityIsThePlanarOne:FlowSolver3d.FlatLayersUnderGravityStayAtRest:SoilPhase3d.ALayerIndependentWaterColumnIsThePlanarOne:SoilPhase3d.WaterLeavesThroughAnOpenSideAsInThePlanarRun:SoilPhase3d.AGranularColumnSpreadsAsTheAxisymmetricOne:AirBand.AColumnOnAMeshOfLayersMovesAsInTheWholeDomain:Obstacles3d.BlockedFloorAndWallsAreTheDomainsOwn:Obstacles3d.AFloorOfAHeightMapIsTheDomainsOwn:Periodic3d.*:SlidingChannel.*:SoilMaterials3d.*:Inlet.*:SurfaceTension.*)
set_tests_properties(flow_3d_2_ranks PROPERTIES
  LABELS parallel TIMEOUT 300
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# granflow stability --restart on 2 ranks: the earlier trials, read by rank 0, are every rank's.
add_test(NAME cli_stability_restart_2_ranks
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/stability_restart.sh $<TARGET_FILE:granflow>
                 ${CMAKE_SOURCE_DIR}/cases/slope_griffiths_lane1999.toml ${CMAKE_CURRENT_BINARY_DIR}/stability_restart_2_ranks
                 ${MPIRUN} -np 2 --oversubscribe)
set_tests_properties(cli_stability_restart_2_ranks PROPERTIES
  LABELS parallel TIMEOUT 300
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# The suites that run two ranks take both cores: beside another test their ranks would share them and
# run at half speed.
set_tests_properties(parallel_tests_2_ranks flow_3d_2_ranks PROPERTIES PROCESSORS 2)
