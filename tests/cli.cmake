# The command line: bad input gets one clear message and a non-zero exit.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/misspelt.toml "[mesh]\ncells = [4, 4]\nupper = [1.0, 1.0]\nupeer = 3\n")
add_test(NAME cli_check_misspelt_key_message COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check ${CMAKE_CURRENT_BINARY_DIR}/misspelt.toml)
set_tests_properties(cli_check_misspelt_key_message PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: [^ ]*misspelt.toml: mesh.upeer: unknown key")
# A case that starts without soil, fed by an inlet, is valid and says where its soil comes from; without
# the inlet's soil it names the missing shapes; an obstacle against the inlet is refused.
add_test(NAME cli_check_case_fed_by_an_inlet
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "\"$0\" check \"$1\" && \"$0\" check \"$1\" --set 'boundary.west={type=\"inlet\", velocity=[0.3, 0.0]}'; echo status $?; \"$0\" check \"$1\" --set \"obstacle=[{shape='box', lower=[0.0,0.01], upper=[0.002,0.012]}]\"; echo status $?"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/chute_inlet.toml)
set_tests_properties(cli_check_case_fed_by_an_inlet PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^[^\n]*chute_inlet.toml: valid [(]200 x 30 cells, t_end = 3 s. initial soil 0 m.2 per metre of depth [(]an inlet brings the soil[)][)]\nerror: [^\n]*initial: missing table [[][[]initial.soil[]][]] [^\n]*\nstatus 2\nerror: [^\n]*chute_inlet.toml: obstacle: the cell at x = 0.00025 m, y = 0.01025 m is blocked against the inlet on the west side, whose flow would enter it. keep the obstacles off the inlet's side\nstatus 2\n$")
# A key nested 100 000 levels deep (a dotted key of 100 000 parts) is read like any other, not a
# stack overflow in the TOML parser.
string(REPEAT "a." 100000 GRANFLOW_DEEP_KEY)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/deep_key.toml "${GRANFLOW_DEEP_KEY}b = 1\n")
add_test(NAME cli_check_deeply_nested_key
         COMMAND sh -c "out=$(\"$0\" check \"$1\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'deep_key.toml: mesh: missing table'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/deep_key.toml)
set_tests_properties(cli_check_deeply_nested_key PROPERTIES LABELS cli)
add_test(NAME cli_run_missing_file
         COMMAND sh -c "out=$(\"$0\" run \"$1\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'no_such_case.toml: cannot open the case file'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/no_such_case.toml)
set_tests_properties(cli_run_missing_file PROPERTIES LABELS cli)
# A file read is a whole file: a read error is named (it was taken for the end of the file, and a case
# cut short ran with defaults), and a device that never ends is not read until memory runs out.
add_test(NAME cli_check_unreadable_case COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check /proc/self/mem)
set_tests_properties(cli_check_unreadable_case PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: /proc/self/mem: cannot read the case file: Input/output error\n$")
add_test(NAME cli_check_endless_case COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check /dev/zero)
set_tests_properties(cli_check_endless_case PROPERTIES LABELS cli TIMEOUT 60
                     PASS_REGULAR_EXPRESSION "^error: /dev/zero: longer than 64 MiB, not a case file")
add_test(NAME cli_check_endless_points_file
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 --set "initial.soil=[{shape = \"polygon\", points_file = \"/dev/zero\"}]")
set_tests_properties(cli_check_endless_points_file PROPERTIES LABELS cli TIMEOUT 60
                     PASS_REGULAR_EXPRESSION "'/dev/zero' is longer than 256 MiB, not a file of points")
add_test(NAME cli_restart_without_checkpoint
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 $<TARGET_FILE:granflow> run ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml
                 -o ${CMAKE_CURRENT_BINARY_DIR}/no_such_run --restart)
set_tests_properties(cli_restart_without_checkpoint PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: no checkpoint to restart from")
# ... and leaves no output directory behind where there was none.
add_test(NAME cli_failed_restart_leaves_no_directory
         COMMAND sh -c "rm -rf \"$1\"; out=$(\"$0\" run \"$2\" -o \"$1\" --restart 2>&1); test $? -eq 1 && test ! -e \"$1\" && echo \"$out\" | grep -q 'no checkpoint to restart from .*: no such directory'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/no_such_run_left
                 ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_failed_restart_leaves_no_directory PROPERTIES LABELS cli)
add_test(NAME cli_element_test_csv COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> element-test --csv)
set_tests_properties(cli_element_test_csv PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "deformation,theta_deg,model,eta_norm_D_over_p,norm_Tdev_over_p,relative\n.*TXC,-30.000000,MC,0.428352,0.856705,1.440269")
# Every shipped case file validates.
file(GLOB GRANFLOW_SHIPPED_CASES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/cases/*.toml)
foreach(case_file ${GRANFLOW_SHIPPED_CASES})
  get_filename_component(case_name ${case_file} NAME_WE)
  add_test(NAME cli_check_case_${case_name} COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> check ${case_file})
  set_tests_properties(cli_check_case_${case_name} PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION ": valid [(]")
endforeach()
# A new run into a directory that holds an earlier run is refused, and the earlier run is kept;
# --overwrite replaces it, and its checkpoint with it.
set(GRANFLOW_SHORT_RUN --set "mesh.cells=[20,20]" --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0)
add_test(NAME cli_run_into_earlier_run_refused
         COMMAND sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; cp \"$d/history.csv\" \"$d/kept\"; out=$(\"$g\" run \"$c\" -o \"$d\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'holds an earlier run' && cmp -s \"$d/history.csv\" \"$d/kept\" && \"$g\" run \"$c\" -o \"$d\" --overwrite \"$@\" > /dev/null"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/earlier_run ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_run_into_earlier_run_refused PROPERTIES LABELS cli)
# An output directory inside another run's checkpoint (which that run replaces whole at its next
# output) is refused for a run and for a strength analysis, with status 2 and nothing made there.
add_test(NAME cli_output_inside_a_runs_checkpoint_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d/checkpoint/inner\" \"$@\" 2>&1; test $? -eq 2 || exit 1; \"$g\" stability \"$c\" -o \"$d/./checkpoint.old/s\" 2>&1; test $? -eq 2 || exit 1; test ! -e \"$d/checkpoint/inner\" && test ! -e \"$d/checkpoint.old\" && echo nothing made"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/output_inside ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_output_inside_a_runs_checkpoint_refused PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "-o [^\n]*/checkpoint/inner: inside [^\n]*/output_inside/checkpoint, which the run in [^\n]*/output_inside replaces whole.*\n.*-o [^\n]*checkpoint.old/s: inside [^\n]*/output_inside/checkpoint.old, which the run .*nothing made")
# A restart whose end is not past the checkpoint, and a damaged checkpoint, are named.
add_test(NAME cli_restart_end_before_checkpoint
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_end ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_end_before_checkpoint PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: time.end = 0.02 s is not past the checkpoint's t = 0.02 s")
add_test(NAME cli_restart_damaged_checkpoint
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; sed -i 's/^output_index .*/output_index abc/' \"$d/checkpoint/run.txt\"; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.05 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_damaged ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_damaged_checkpoint PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "checkpoint is damaged: .*run.txt: 'abc' is not a count for 'output_index'")
add_test(NAME cli_restart_damaged_clock
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; sed -i 's/^time .*/time garbage/' \"$d/checkpoint/run.txt\"; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.05 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_clock ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_damaged_clock PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "checkpoint is damaged: .*run.txt: the clock \\(time nan")
# A checkpoint that the file system does not take whole (a full disk, made here by failing every write
# of the MPI-IO layer, which Open MPI 4.1 reports as a success) stops the run with a message, and the
# checkpoint before it stays as it was.
find_program(GRANFLOW_STRACE strace REQUIRED)
add_test(NAME cli_checkpoint_on_a_full_disk_is_named
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; s=$1; d=$2; c=$3; shift 3; rm -rf \"$d\" \"$d.kept\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; cp \"$d/checkpoint/fields.bin\" \"$d.kept\"; out=$(\"$s\" -f -o /dev/null -e inject=pwrite64,pwritev:error=ENOSPC \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.04 2>&1); status=$?; echo \"$out\" | grep '^error'; test $status -eq 1 && cmp -s \"$d/checkpoint/fields.bin\" \"$d.kept\" && echo earlier checkpoint kept"
                 $<TARGET_FILE:granflow> ${GRANFLOW_STRACE} ${CMAKE_CURRENT_BINARY_DIR}/full_disk
                 ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_checkpoint_on_a_full_disk_is_named PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION
  "^error: cannot write [^\n]*checkpoint.partial/fields.bin: what it holds is not what was written [(]is the disk full[?][)]\nearlier checkpoint kept\n$")
# A run out of steps says so; a restart must raise time.max_steps, which counts the whole run's.
add_test(NAME cli_max_steps_said
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" --set time.max_steps=3 2>&1 || exit 1; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.max_steps=3 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/max_steps ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_max_steps_said PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION
                     "in 3 steps [^\n]*, stopped at time.max_steps = 3 before time.end = 0.02 s\n.*error: time.max_steps = 3 is not past the checkpoint's 3 steps")
add_test(NAME cli_restart_other_domain
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.05 --set mesh.upper=[0.7,0.2] 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_domain ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_other_domain PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "the checkpoint is of the domain \\[0, 0.6\\] x \\[0, 0.2\\] \\(planar\\). the case's is \\[0, 0.7\\]")
add_test(NAME cli_restart_other_grading
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.05 --set mesh.grading=[5,0.2] 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_grading ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_other_grading PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "the checkpoint is of the domain [^\n]*\\(planar\\). the case's is [^\n]*\\(planar\\), grading \\[5, 0.2\\]")
# A restart honours a lower time.max_dt from its first step (the stopped run's next step was 1.4 ms).
add_test(NAME cli_restart_takes_the_new_max_dt
         COMMAND sh -c "g=$0; d=$1; c=$2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set time.end=0.1 --set 'mesh.cells=[74,32]' --set 'mesh.upper=[0.35242, 0.1524]' --set output.fields=false --set output.progress_seconds=0 > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d\" --restart --set time.end=0.101 --set time.max_dt=1e-4 --set 'mesh.cells=[74,32]' --set 'mesh.upper=[0.35242, 0.1524]' --set output.fields=false --set output.progress_seconds=0 > /dev/null || exit 1; awk -F, 'NR > 1 && $1 > 0.1 + 1e-9 { n++; if ($2 > 1.0000001e-4) bad++ } END { exit !(n >= 10 && bad == 0) }' \"$d/history.csv\""
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_max_dt ${CMAKE_SOURCE_DIR}/cases/water_dam_break.toml)
set_tests_properties(cli_restart_takes_the_new_max_dt PROPERTIES LABELS cli)
# An output path that is a file, a misspelt command, a solver PETSc does not know, a PETSc option
# nothing reads.
add_test(NAME cli_output_is_a_file
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 sh -c "touch \"$1\"; \"$0\" run \"$2\" -o \"$1\" 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/output_file ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_output_is_a_file PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "error: -o [^\n]*output_file: not a directory")
add_test(NAME cli_output_is_a_file_overwrite
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "touch \"$1\"; \"$0\" run \"$2\" -o \"$1\" --overwrite 2>&1; status=$?; test -f \"$1\" && echo file kept; test $status -eq 2"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/output_file_overwrite ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_output_is_a_file_overwrite PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "^error: -o [^\n]*output_file_overwrite: not a directory\nfile kept\n$")
# --overwrite keeps the earlier run when PETSc refuses an option of the coupled solve's region (its
# solver is made in the first step; its options are read before the earlier run goes): status 2.
add_test(NAME cli_overwrite_keeps_the_run_when_petsc_refuses_an_option
         COMMAND sh -c "g=$0; d=$1; c=$2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[30,10]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; cp \"$d/history.csv\" \"$d/kept\"; out=$(\"$g\" run \"$c\" -o \"$d\" --overwrite --set 'mesh.cells=[30,10]' '--petsc=-coupled_pc_type nonsense' 2>&1); status=$?; test $status -eq 2 && echo \"$out\" | grep -q 'PC type nonsense' && cmp -s \"$d/history.csv\" \"$d/kept\" && test -f \"$d/checkpoint/run.txt\""
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/overwrite_bad_petsc ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_overwrite_keeps_the_run_when_petsc_refuses_an_option PROPERTIES LABELS cli)
# --overwrite keeps the earlier run when the new run fails before its first step is taken (here its
# coupled solve diverges at every length of step: an over-relaxed Richardson iteration): the earlier
# run's files, set aside, come back, and none of the new run's is left.
add_test(NAME cli_overwrite_keeps_the_run_when_the_first_step_fails
         COMMAND sh -c "g=$0; d=$1; c=$2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[30,10]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; cp \"$d/history.csv\" /tmp/granflow_kept_$$; ls -a \"$d\" > /tmp/granflow_list_$$; \"$g\" run \"$c\" -o \"$d\" --overwrite --set 'mesh.cells=[30,10]' --set time.end=0.01 '--petsc=-coupled_ksp_type richardson -coupled_ksp_richardson_scale 1000 -coupled_pc_type none' > /dev/null 2>&1; status=$?; ls -a \"$d\" | cmp -s - /tmp/granflow_list_$$ && cmp -s \"$d/history.csv\" /tmp/granflow_kept_$$; same=$?; rm -f /tmp/granflow_kept_$$ /tmp/granflow_list_$$; test $status -eq 3 && test $same -eq 0 && test -f \"$d/surface_00002.csv\" && test -f \"$d/checkpoint/run.txt\""
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/overwrite_first_step_fails ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_overwrite_keeps_the_run_when_the_first_step_fails PROPERTIES LABELS cli)
# The same when the first step diverges (a lid at 1e8 m/s): the step is not an accepted one.
add_test(NAME cli_overwrite_keeps_the_run_when_the_first_step_diverges
         COMMAND sh -c "g=$0; d=$1; c=$2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[8,8]' --set time.end=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; cp \"$d/u_vertical_centreline.csv\" \"$d.kept\"; said=$(\"$g\" run \"$c\" -o \"$d\" --overwrite --set 'mesh.cells=[8,8]' --set time.adaptive=false --set time.dt=0.01 --set 'boundary.north={type = \"wall\", velocity = [1e8, 0.0]}' 2>&1 > /dev/null); status=$?; cmp -s \"$d/u_vertical_centreline.csv\" \"$d.kept\" && test $status -eq 3 && echo \"$said\" | grep -q \"diverged.*the earlier run's files are put back in $d\" && test -f \"$d/fields_00001.vtr\" && test -f \"$d/checkpoint/run.txt\" && test ! -e \"$d/.replaced_run\""
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/overwrite_first_step_diverges ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_overwrite_keeps_the_run_when_the_first_step_diverges PROPERTIES LABELS cli)
# A run set aside by --overwrite and left there (the new run was killed before its first step) is the
# only copy of that run: a run into the directory is refused, naming it, and it is left as it is.
add_test(NAME cli_set_aside_run_left_by_a_killed_run_is_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "d=$1; rm -rf \"$d\"; mkdir -p \"$d/.replaced_run\" && echo x > \"$d/.replaced_run/history.csv\"; \"$0\" run \"$2\" -o \"$d\" --overwrite --set 'mesh.cells=[8,8]' --set time.end=0.01 2>&1; status=$?; test -f \"$d/.replaced_run/history.csv\" && echo kept; test $status -eq 2"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/set_aside_left ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_set_aside_run_left_by_a_killed_run_is_refused PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "^error: [^\n]*set_aside_left holds [^\n]*\\.replaced_run, the files of an earlier run that a run with --overwrite set aside[^\n]*\nkept\n$")
# --overwrite leaves none of the earlier run's files: a shorter run does not keep the longer one's
# later outputs. A run that wrote only line samples is an earlier run too.
add_test(NAME cli_overwrite_removes_the_earlier_run
         COMMAND sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" --set time.end=0.04 > /dev/null && test -f \"$d/surface_00004.csv\" && \"$g\" run \"$c\" -o \"$d\" --overwrite \"$@\" > /dev/null && ! ls \"$d\" | grep -q '_0000[34]' && test -f \"$d/surface_00002.csv\" && test ! -e \"$d/.replaced_run\""
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/overwrite_removes ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_overwrite_removes_the_earlier_run PROPERTIES LABELS cli)
add_test(NAME cli_earlier_run_of_line_samples_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d\" \"$@\" 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/earlier_lines ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml
                 --set "mesh.cells=[8,8]" --set time.end=0.02 --set output.fields=false --set output.checkpoints=false --set output.progress_seconds=0)
set_tests_properties(cli_earlier_run_of_line_samples_refused PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "holds an earlier run [(][^)]*(granflow_run.txt|granflow_case.toml|centreline)[^)]*[)]")
add_test(NAME cli_unknown_command COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> runn ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_unknown_command PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "error: unknown command 'runn'")
add_test(NAME cli_check_unknown_solver
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml --set solver.coupled.ksp_type=bogus)
set_tests_properties(cli_check_unknown_solver PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "solver.coupled.ksp_type: 'bogus' is not a Krylov method")
# Options may come before the case file, each --set taking one value; blanks around a key are the
# TOML line's; a command line that is refused is status 2, as a refused case is.
add_test(NAME cli_options_before_the_case_and_status_2
         COMMAND sh -c "\"$0\" check --set 'time.end = 0.05' --petsc=-log_view \"$1\" --set output.fields=false | grep -q 't_end = 0.05 s' && \"$0\" check \"$1\" --bogus; test $? -eq 2"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/water_dam_break.toml)
set_tests_properties(cli_options_before_the_case_and_status_2 PROPERTIES LABELS cli)
# check takes a run's --petsc: valid options pass, an unreadable options file is exit 2 with its name.
add_test(NAME cli_check_takes_the_runs_petsc_options
         COMMAND sh -c "\"$0\" check \"$1\" --petsc=-coupled_ksp_monitor | grep -q ': valid (' && out=$(\"$0\" check \"$1\" '--petsc=-options_file /no/such/options' 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'cannot read /no/such/options'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_check_takes_the_runs_petsc_options PROPERTIES LABELS cli)
# Obstacles are laid out by check as by a run: one that holds no cell centre, obstacles that block
# every cell, and initial soil only in blocked cells are each exit 2 with the message.
add_test(NAME cli_check_lays_out_the_obstacles
         COMMAND sh -c "for bad in \"obstacle=[{shape='box', lower=[0.401,0.0], upper=[0.402,0.01]}]|the shape holds no cell centre on this 30 x 10 mesh\" \"obstacle=[{shape='box', lower=[-1,-1], upper=[1,1]}]|the obstacles block every cell\" \"obstacle=[{shape='box', lower=[-1,-1], upper=[0.3,0.15]}]|the shapes place no soil in any open cell\" \"obstacle=[{shape='box', lower=[0.41,0.0], upper=[0.42,0.1]}]|is a wall one cell thick\" \"obstacle=[{shape='box', lower=[0.3,0.1], upper=[0.5,0.16]}, {shape='box', lower=[0.3,0.0], upper=[0.34,0.1]}, {shape='box', lower=[0.46,0.0], upper=[0.5,0.1]}]|are closed off by the obstacles\"; do out=$(\"$0\" check \"$1\" --set 'mesh.cells=[30,10]' --set \"\${bad%%|*}\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q \"^error: $1: .*\${bad#*|}\" || { echo \"$out\"; exit 1; }; done"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/barrier_collapse.toml)
set_tests_properties(cli_check_lays_out_the_obstacles PROPERTIES LABELS cli)
# The overburden of soil.yield_pressure = "lithostatic_floor" would be taken through an obstacle: refused.
add_test(NAME cli_check_lithostatic_floor_with_obstacles_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/barrier_collapse.toml
                 --set soil.yield_pressure=lithostatic_floor --set soil.strain_rate=cell --set soil.face_fraction=cells)
set_tests_properties(cli_check_lithostatic_floor_with_obstacles_refused PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*barrier_collapse.toml: obstacle: soil.yield_pressure = \"lithostatic_floor\" takes the soil above each cell up to the top, through any obstacle. use \"face\" or \"cell\" with obstacles\n$")
# check lays out the initial state as a run does, and finds what only that shows: exit 2 and the message.
add_test(NAME cli_check_lays_out_the_initial_state
         COMMAND sh -c "out=$(\"$0\" check \"$1\" --set 'mesh.cells=[30,10]' --set \"$2\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q \"^error: $1: initial.soil: the shapes cover no part of any cell's samples on this 30 x 10 mesh\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 "initial.soil=[{shape = \"box\", lower = [0.3, 0.1], upper = [0.3001, 0.1001]}]")
set_tests_properties(cli_check_lays_out_the_initial_state PROPERTIES LABELS cli)
# A run of the cavity on 8 x 8 cells to t = 0.01 s into its own directory, for the --petsc tests.
set(GRANFLOW_TINY_CAVITY_RUN --overwrite --set "mesh.cells=[8,8]" --set time.end=0.01 --set output.progress_seconds=0)
add_test(NAME cli_unused_petsc_option
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> run ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml -o ${CMAKE_CURRENT_BINARY_DIR}/unused_option
                 ${GRANFLOW_TINY_CAVITY_RUN}
                 --petsc=-presure_ksp_monitor)
set_tests_properties(cli_unused_petsc_option PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "warning: PETSc option -presure_ksp_monitor was given but not used")
# check warns of the PETSc options the run's solvers would not read, as run does at its end: a
# misspelt prefix or name, a solver the case does not make (the cavity's u and v share one momentum
# solver; the collapse's coupled solve makes none), not an option MUMPS or GAMG reads at set-up, nor a
# monitor of a solver the run makes. Only stderr is matched (status 0 checked).
add_test(NAME cli_check_unused_petsc_options
         COMMAND sh -c "\"$0\" check \"$1\" '--petsc=-presure_ksp_monitor -pressure_ksp_monitor -pressure_pc_type gamg -pressure_pc_gamg_threshold 0.02 -momentum_y_ksp_type cg' 2>&1 >/dev/null || exit 1; \"$0\" check \"$2\" '--petsc=-coupled_ksp_monitr -coupled_ksp_monitor -coupled_mat_mumps_icntl_14 40 -momentum_x_ksp_type cg' 2>&1 >/dev/null"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_check_unused_petsc_options PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^warning: PETSc option -momentum_y_ksp_type was given but not used [^\n]*\nwarning: PETSc option -presure_ksp_monitor was given but not used [^\n]*\nwarning: PETSc option -coupled_ksp_monitr was given but not used [^\n]*\nwarning: PETSc option -momentum_x_ksp_type was given but not used [^\n]*\n$")
# Another preconditioner reads none of the BoomerAMG defaults granflow sets: no warning for those.
add_test(NAME cli_other_preconditioner_no_warning
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> run ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml -o ${CMAKE_CURRENT_BINARY_DIR}/other_pc
                 ${GRANFLOW_TINY_CAVITY_RUN}
                 "--petsc=-pressure_pc_type gamg")
set_tests_properties(cli_other_preconditioner_no_warning PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "done: t = 0.01 s"
                     FAIL_REGULAR_EXPRESSION "was given but not used;error:")
# PETSc options read at start-up (-log_view) work through --petsc, and one --petsc may hold several.
add_test(NAME cli_petsc_start_up_option
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> run ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml -o ${CMAKE_CURRENT_BINARY_DIR}/log_view
                 ${GRANFLOW_TINY_CAVITY_RUN}
                 "--petsc=-log_view -pressure_ksp_rtol 1e-9")
set_tests_properties(cli_petsc_start_up_option PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "Summary of Stages"
                     FAIL_REGULAR_EXPRESSION "PETSC ERROR;was given but not used;error:")
# An options file PETSc cannot read is named in one line, before PETSc stops with its error trace.
add_test(NAME cli_petsc_missing_options_file
         COMMAND sh -c "out=$(\"$0\" run \"$1\" -o \"$2\" --overwrite \"--petsc=-options_file $2/no_such_file\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'error: --petsc -options_file: cannot read .*no_such_file' && ! echo \"$out\" | grep -q 'PETSC ERROR'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/options_file)
set_tests_properties(cli_petsc_missing_options_file PROPERTIES LABELS cli)
# Options files that include themselves (directly or through another; PETSc would recurse until its
# stack ran out), a device that never ends, and a line PETSc cannot parse: each refused in one line,
# status 2, without PETSc's trace.
add_test(NAME cli_petsc_options_files_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\"; mkdir -p \"$d\" && cd \"$d\" || exit 1; echo '-options_file self.opts' > self.opts; echo '-options_file b.opts' > a.opts; printf '%s\\n' '-coupled_ksp_monitor' '-options_file a.opts # back' > b.opts; echo 'coupled_ksp_monitor' > bad.opts; for w in self.opts a.opts /dev/zero bad.opts; do out=$(\"$g\" check \"$c\" \"--petsc=-options_file $w\" 2>&1); s=$?; echo \"$out\"; test $s -eq 2 || exit 1; echo \"$out\" | grep -q 'PETSC ERROR' && exit 1; done; exit 0"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/options_files)
set_tests_properties(cli_petsc_options_files_refused PROPERTIES LABELS cli TIMEOUT 60
                     PASS_REGULAR_EXPRESSION "error: --petsc -options_file: self.opts includes itself \\([^)]*/self.opts -> [^)]*/self.opts\\)\nerror: --petsc -options_file: a.opts includes itself \\([^)]*/a.opts -> [^)]*/b.opts -> [^)]*/a.opts\\)\nerror: --petsc -options_file: /dev/zero is longer than 1 MiB, not an options file\nerror: PETSc could not start: Unknown first token in options file bad.opts line 1: coupled_ksp_monitor")
# The same checks for the options PETSc reads from the environment's PETSC_OPTIONS, named so.
add_test(NAME cli_petsc_environment_options_files_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\"; mkdir -p \"$d\" && cd \"$d\" || exit 1; echo '-options_file self.opts' > self.opts; for o in '-options_file self.opts' '-options_file missing.opts' '-log_view :no_such_dir/log.txt'; do out=$(PETSC_OPTIONS=\"$o\" \"$g\" run \"$c\" -o run --set 'mesh.cells=[8,8]' 2>&1); s=$?; echo \"$out\"; test $s -eq 2 || exit 1; test -e run && exit 1; echo \"$out\" | grep -q 'PETSC ERROR' && exit 1; done; exit 0"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/environment_options)
set_tests_properties(cli_petsc_environment_options_files_refused PROPERTIES LABELS cli TIMEOUT 60
                     PASS_REGULAR_EXPRESSION "^error: PETSC_OPTIONS -options_file: self.opts includes itself \\([^)]*/self.opts -> [^)]*/self.opts\\)\nerror: PETSC_OPTIONS -options_file: cannot read missing.opts: No such file or directory\nerror: PETSC_OPTIONS -log_view :no_such_dir/log.txt: cannot write no_such_dir/log.txt\n$")
# A tolerance that PETSc's options set outside the case file's range (a relative tolerance of 2 stops
# every solve before its first iteration, a negative iteration limit at once) is refused before the
# run, with status 2 and no output directory made.
add_test(NAME cli_petsc_tolerance_out_of_range
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\"; for o in '-pressure_ksp_rtol 2' '-pressure_ksp_max_it -5' '-pressure_ksp_divtol -3'; do \"$g\" run \"$c\" -o \"$d\" --set time.end=0.01 \"--petsc=$o\" 2>&1; test $? -eq 2 || exit 1; test -e \"$d\" && exit 1; done; exit 0"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/tolerance_out_of_range)
set_tests_properties(cli_petsc_tolerance_out_of_range PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: linear solver 'pressure': rtol = 2 \\(solver.pressure.rtol, or PETSc's -pressure_ksp_rtol\\) must be within \\[0, 1\\)\nerror: linear solver 'pressure': max_iterations = -5 \\(solver.pressure.max_iterations, or PETSc's -pressure_ksp_max_it\\) must be at least 1\nerror: linear solver 'pressure': PETSc's -pressure_ksp_divtol = -3 must be at least 1")
# preonly with a preconditioner that does not factorise is an inexact solve nothing counts: warned
# of once, naming the solver; with lu, not.
add_test(NAME cli_preonly_without_factorisation_warned
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\" \"$d.lu\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[8,8]' --set time.end=0.01 --set output.fields=false --set solver.pressure.ksp_type=preonly --set solver.pressure.pc_type=jacobi 2>&1 >/dev/null || exit 1; \"$g\" run \"$c\" -o \"$d.lu\" --set 'mesh.cells=[8,8]' --set time.end=0.01 --set output.fields=false --set solver.pressure.ksp_type=preonly --set solver.pressure.pc_type=lu 2>&1 >/dev/null"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/preonly_jacobi)
set_tests_properties(cli_preonly_without_factorisation_warned PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^warning: linear solver 'pressure' applies pc_type = jacobi once \\(ksp_type = preonly\\), which solves only with a factorisation \\(lu, cholesky\\)[^\n]*\n$")
# Inexact coupled solves (preonly with jacobi) make and destroy soil: the run's last lines say by how
# much; the same run with the default factorisation keeps it to round-off and says nothing.
add_test(NAME cli_soil_volume_change_warned
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\" \"$d.lu\"; lu=$(\"$g\" run \"$c\" -o \"$d.lu\" --set 'mesh.cells=[60,20]' --set time.end=0.05 --set output.fields=false --set output.progress_seconds=0 2>&1) || exit 1; if echo \"$lu\" | grep -q 'soil.s volume'; then echo \"$lu\"; exit 1; fi; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[60,20]' --set time.end=0.05 --set output.fields=false --set output.progress_seconds=0 --set solver.coupled.pc_type=jacobi 2>/dev/null"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/soil_volume_jacobi)
set_tests_properties(cli_soil_volume_change_warned PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "\nwarning: the soil's volume, with what left through open sides, changed by -[0-9.]+ % over the run \\(round-off keeps it within 1e-11 %\\): the linear solves were not exact")
# A -log_view file that cannot be written is refused before the run, not found at its end; the
# output directory is not made.
add_test(NAME cli_petsc_unwritable_log_view
         COMMAND sh -c "rm -rf \"$2\"; out=$(\"$0\" run \"$1\" -o \"$2\" \"--petsc=-log_view :$2/no/such/dir/log.txt\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'error: --petsc -log_view .*: cannot write .*no/such/dir/log.txt' && test ! -e \"$2\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/log_view_run)
set_tests_properties(cli_petsc_unwritable_log_view PROPERTIES LABELS cli)
# Each field file carries its time where VTK's readers look for it: in the data set's field data,
# before its piece (ParaView reading the files as a series, or one file in Python, gets the time).
add_test(NAME cli_field_file_carries_its_time
         COMMAND sh -c "\"$0\" run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[8,8]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; tr -d '\\n' < \"$2/fields_00001.vtr\" | grep -q '<RectilinearGrid [^>]*><FieldData><DataArray type=.Float64. Name=.TimeValue. NumberOfTuples=.1. format=.ascii.>0[.]01</DataArray></FieldData><Piece '"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/field_time)
set_tests_properties(cli_field_file_carries_its_time PROPERTIES LABELS cli)
# A line sample on an obstacle's faces (x = 0.4 and 0.412 m, both computed to round-off) takes the
# wall's values; only the points inside it are nan.
add_test(NAME cli_line_sample_on_obstacle_faces
         COMMAND sh -c "{ cat \"$1\"; printf '[[output.line]]\\nname = \"floor\"\\nstart = [0.0, 0.002]\\nend = [0.6, 0.002]\\npoints = 151\\n'; } > \"$2.toml\" && \"$0\" run \"$2.toml\" -o \"$2\" --overwrite --set time.end=0.01 --set output.fields=false --set output.progress_seconds=0 > /dev/null && grep -E '^0[.](4|412),0[.]002,[-0-9]' \"$2/floor.csv\" | wc -l | grep -qx 2 && grep -E '^0[.](404|408),0[.]002,nan,' \"$2/floor.csv\" | wc -l | grep -qx 2"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/barrier_collapse.toml ${CMAKE_CURRENT_BINARY_DIR}/line_sample_obstacle)
set_tests_properties(cli_line_sample_on_obstacle_faces PROPERTIES LABELS cli)
# check says what it laid out: the soil the shapes place, and the cells the obstacles block.
add_test(NAME cli_check_says_what_it_laid_out
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/barrier_collapse.toml)
set_tests_properties(cli_check_says_what_it_laid_out PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "valid [(]150 x 50 cells, t_end = 2 s. initial soil 0[.]02 m\\^2 per metre of depth. 21 cells blocked by obstacles[)]")
# ... and the part of the initial shapes that lies in obstacles and is left out: a box reaching 1 cm
# into the barrier's 2.8 cm height (2.8e-4 m^2).
add_test(NAME cli_check_says_what_obstacles_leave_out
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/barrier_collapse.toml
                 --set "initial.soil=[{shape='box', lower=[0.0,0.0], upper=[0.41,0.1]}]")
set_tests_properties(cli_check_says_what_obstacles_leave_out PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "valid [(]150 x 50 cells, t_end = 2 s. initial soil 0[.]04072 m\\^2 per metre of depth. 21 cells blocked by obstacles, which leave out 0[.]00028 m\\^2 per metre of depth of the initial shapes' soil[)]")
# On a mesh of layers obstacles are solids (a sphere here), laid out and checked as on a planar one:
# check counts the cells they block, and names a wall one cell thick by its three coordinates.
add_test(NAME cli_check_lays_out_obstacles_of_layers
         COMMAND sh -c "out=$(\"$0\" check \"$1\" --set \"obstacle=[{shape='sphere', centre=[0.3,0.0,0.3], radius=0.05}]\" 2>&1) && echo \"$out\" | grep -q '40 x 16 x 40 cells.*276 cells blocked by obstacles' || { echo \"$out\"; exit 1; }; out=$(\"$0\" check \"$1\" --set \"obstacle=[{shape='box', lower=[0.25,0,0.2], upper=[0.35,0.05,0.21]}]\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'x = 0.255 m, y = 0.005 m, z = 0.205 m is a wall one cell thick' || { echo \"$out\"; exit 1; }"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lube2004_a05_3d.toml)
set_tests_properties(cli_check_lays_out_obstacles_of_layers PROPERTIES LABELS cli)
# Terrain from an elevation model (cases/terrain/valley.asc, a height map) under a slab of soil: the
# cells whose centre lies under the valley's surface are blocked, and the slab holds the soil above the
# terrain, as counted independently by sampling each cell's 16^3 points against the same surfaces.
add_test(NAME cli_check_lays_out_terrain_of_a_height_map
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/terrain_landslide_3d.toml)
set_tests_properties(cli_check_lays_out_terrain_of_a_height_map PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "valid [(]40 x 20 x 15 cells, t_end = 3 s. initial soil 0[.]00356 m\\^3. 2400 cells blocked by obstacles, which leave out 0[.]01024 m\\^3 of the initial shapes' soil[)]")
# A height map rougher than the cells: a node 6 cm above its neighbours on the 2 cm cells stands in one
# column, a ridge one cell wide, which is lowered to the mesh: its three cells above the neighbours'
# three are opened (30 blocked less 3, 3 x 8e-6 m^3). Asked to refuse it, check says where the wall is.
set(SPIKED_MAP "obstacle=[{shape='height_map', origin=[0.39, 0.13], spacing=[0.02, 0.02], heights=[[0.06, 0.06, 0.06], [0.06, 0.12, 0.06], [0.06, 0.06, 0.06]]}]")
add_test(NAME cli_check_lowers_the_thin_ridges_of_a_height_map
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/terrain_landslide_3d.toml --set "${SPIKED_MAP}")
set_tests_properties(cli_check_lowers_the_thin_ridges_of_a_height_map PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION " 27 cells blocked by obstacles. 3 cells of ridges one cell wide lowered to the mesh [(]obstacle\\[0\\]: 3, 2[.]4e-05 m\\^3[)]")
string(REPLACE "shape='height_map'," "shape='height_map', thin_ridges='refuse'," SPIKED_MAP_REFUSED "${SPIKED_MAP}")
add_test(NAME cli_check_refuses_the_thin_ridges_of_a_height_map_when_asked
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/terrain_landslide_3d.toml --set "${SPIKED_MAP_REFUSED}")
set_tests_properties(cli_check_refuses_the_thin_ridges_of_a_height_map_when_asked PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: [^\n]*terrain_landslide_3d.toml: obstacle: the cell at x = 0[.]41 m, y = 0[.]07 m, z = 0[.]15 m is a wall one cell thick")
# The same ridge on the ranks' boundary (x = 0.4 m on 40 cells), lowered alike on
# two ranks: the same cells blocked as on one (cli_check_lowers_the_thin_ridges_of_a_height_map).
add_test(NAME cli_check_2_ranks_lowers_the_thin_ridges_of_a_height_map
         COMMAND ${MPIRUN} -np 2 --oversubscribe $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/terrain_landslide_3d.toml --set "${SPIKED_MAP}")
set_tests_properties(cli_check_2_ranks_lowers_the_thin_ridges_of_a_height_map PROPERTIES
  LABELS parallel TIMEOUT 120
  PASS_REGULAR_EXPRESSION " 27 cells blocked by obstacles. 3 cells of ridges one cell wide lowered to the mesh [(]obstacle\\[0\\]: 3, 2[.]4e-05 m\\^3[)]"
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
# ... and with soil materials, each one's soil; a material whose shapes all lie under later shapes
# holds none, which check finds as a run does (exit 2, the message naming it).
add_test(NAME cli_check_says_each_materials_soil
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/slope_griffiths_lane1999_foundation.toml --set "mesh.cells=[90,30]")
set_tests_properties(cli_check_says_each_materials_soil PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "initial soil 1300 m\\^2 per metre of depth, of which the rheology's own soil 400, foundation 900[)]")
add_test(NAME cli_check_material_under_later_shapes
         COMMAND sh -c "out=$(\"$0\" check \"$1\" --set 'mesh.cells=[90,30]' --set \"$2\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q \"^error: $1: soil.materials\\[0\\]: 'foundation' holds no soil once the shapes are laid out\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/slope_griffiths_lane1999_foundation.toml
                 "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [90, 10], material = \"foundation\"}, {shape = \"box\", lower = [0, 0], upper = [90, 20]}]")
set_tests_properties(cli_check_material_under_later_shapes PROPERTIES LABELS cli)
# A second run into a directory a run is writing into is refused (status 2), with --overwrite or
# --restart too; the second starts once the first has said it is under way, and the first (of some
# ten seconds) is stopped when both have been refused.
add_test(NAME cli_second_run_into_a_busy_directory_refused
         COMMAND sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\" \"$d.log\"; mkdir -p \"$d\"; \"$g\" run \"$c\" -o \"$d\" --overwrite --set 'mesh.cells=[150,50]' --set time.end=2 --set output.progress_seconds=0 > \"$d.log\" 2>&1 & first=$!; k=0; until grep -q 'output in' \"$d.log\"; do k=$((k+1)); test $k -lt 600 || { kill $first; exit 1; }; sleep 0.1; done; for extra in --overwrite --restart; do out=$(\"$g\" run \"$c\" -o \"$d\" $extra --set 'mesh.cells=[150,50]' --set time.end=0.3 2>&1); status=$?; echo \"$out\"; test $status -eq 2 && echo \"$out\" | grep -q 'another granflow run is writing into this directory' || { kill $first; exit 1; }; done; kill $first; wait $first; true"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/busy_directory)
set_tests_properties(cli_second_run_into_a_busy_directory_refused PROPERTIES LABELS cli TIMEOUT 300)
# An output path too long for the run's files under it is refused at once (status 2), not at the
# first checkpoint.
add_test(NAME cli_output_path_too_long
         COMMAND sh -c "out=$(\"$0\" run \"$1\" -o \"/tmp/$(printf '%03900d' 0)\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q '^error: -o: the output directory.s path is 3905 characters long, more than 3800'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_output_path_too_long PROPERTIES LABELS cli)
# A run started with stdout closed ends as asked (status 0), with its files written.
add_test(NAME cli_run_with_stdout_closed
         COMMAND sh -c "\"$0\" run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[8,8]' --set time.end=0.02 >&- && test -s \"$2/fields_00001.vtr\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/stdout_closed)
set_tests_properties(cli_run_with_stdout_closed PROPERTIES LABELS cli)
# An output directory that is a dangling symbolic link is named as such, and a case file that cannot
# be opened says why.
add_test(NAME cli_output_dangling_link_and_case_file_reason
         COMMAND sh -c "ln -sfn \"$2.nowhere\" \"$2\"; out=$(\"$0\" run \"$1\" -o \"$2\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'cannot make the output directory: .*(it is a symbolic link to .*nowhere, which is not a directory)' && out=$(\"$0\" check \"$2.toml\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'cannot open the case file: No such file or directory'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/dangling_link)
set_tests_properties(cli_output_dangling_link_and_case_file_reason PROPERTIES LABELS cli)
# A name in the output path longer than the file system takes is bad input (status 2), named, for
# a restart too.
add_test(NAME cli_output_name_too_long
         COMMAND sh -c "out=$(\"$0\" run \"$1\" -o \"/tmp/$(printf '%0300d' 0)\" --set 'mesh.cells=[8,8]' 2>&1); test $? -eq 2 && echo \"$out\" | grep -q '^error: -o .*: cannot make the output directory: File name too long' && out=$(\"$0\" run \"$1\" --restart -o \"/tmp/$(printf '%0300d' 0)\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q '^error: -o .*: File name too long'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_output_name_too_long PROPERTIES LABELS cli)
# The comparison scripts name a missing or malformed file in one line, not a traceback.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/bad_refdata/ghia1982_cavity_re100.csv "y,u\n0.5,abc\n")
add_test(NAME scripts_compare_missing_run
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/compare_dam_break.py ${CMAKE_CURRENT_BINARY_DIR}/no_such_run)
set_tests_properties(scripts_compare_missing_run PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: cannot read [^\n]*no_such_run/history.csv: No such file or directory\n$")
# A further run for the dam break's plot is read before the report is printed (a missing one stops
# the script at once), and asking for one without a plot is refused instead of ignored.
add_test(NAME scripts_compare_dam_break_further_runs
         COMMAND sh -c "out=$(/usr/bin/python3 \"$0\" \"$1\" --also \"$1\" 2>&1); a=$?; echo \"$out\"; test $a -eq 2 && echo \"$out\" | grep -q 'error: --also adds runs to the plot: give --png FILE too'"
                 ${CMAKE_SOURCE_DIR}/scripts/compare_dam_break.py ${CMAKE_CURRENT_BINARY_DIR}/no_such_run)
set_tests_properties(scripts_compare_dam_break_further_runs PROPERTIES LABELS cli)
add_test(NAME scripts_compare_malformed_refdata
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/compare_cavity.py ${CMAKE_CURRENT_BINARY_DIR}/no_such_run 100
                 --refdata ${CMAKE_CURRENT_BINARY_DIR}/bad_refdata)
set_tests_properties(scripts_compare_malformed_refdata PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*bad_refdata/ghia1982_cavity_re100.csv: not a table of numbers")
# The Bui comparison reads a one-cell toe as the history does, on cells that are not square (the
# layer reaching the floor cell's 5 mm, to the column's east face: 0.31 m, not the 0.22 m that 10 mm
# would give), and refuses a run of another block. Written as a run would write them.
set(GRANFLOW_BUI_FIXTURE ${CMAKE_CURRENT_BINARY_DIR}/bui_fixture)
file(WRITE ${GRANFLOW_BUI_FIXTURE}/column_height_00001.csv
     "# soil height per column (sum of c dy) at t = 2 s\nx,height,x_east,floor_cell_height\n0.1,0.08,0.2,0.005\n0.25,0.006,0.31,0.005\n0.36,0.004,0.41,0.005\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}/surface_00001.csv "# surface at t = 2 s\nx0,y0,x1,y1\n0.0,0.08,0.3,0.003\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}/failure_line_00001.csv "# failure_line at t = 2 s\nx0,y0,x1,y1\n0.1,0.0,0.2,0.05\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}/history.csv
     "time,soil_volume,soil_outflow,kinetic_energy,potential_energy,dissipated_energy\n0.001,0.02,0,0,1.0,0\n2,0.02,0,1e-6,0.5,0.51\n")
# A run stopped before its time.end, whose pile may still move (0.01 J/m in 0.0198 m^2 of soil of 2650
# kg/m^3: a root-mean-square speed of 0.0195 m/s), whose soil partly left the domain, without failure lines (soil.displacement =
# false): compared, with a warning for each and the failure line's distance null.
file(WRITE ${GRANFLOW_BUI_FIXTURE}_partial/column_height_00001.csv
     "# soil height per column (sum of c dy) at t = 2 s\nx,height,x_east,floor_cell_height\n0.1,0.08,0.2,0.005\n0.25,0.006,0.31,0.005\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}_partial/surface_00001.csv "# surface at t = 2 s\nx0,y0,x1,y1\n0.0,0.08,0.3,0.003\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}_partial/history.csv
     "time,soil_volume,soil_outflow,kinetic_energy,potential_energy,dissipated_energy\n0.001,0.02,0,0,1.0,0\n2,0.0198,0.0002,0.01,0.5,0.5\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}_partial/granflow_case.toml "[time]\nend = 3.0\n")
add_test(NAME scripts_compare_bui2008_partial_run
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "/usr/bin/python3 \"$0\" \"$1\" --json \"$1/comparison.json\" 2>&1 && cat \"$1/comparison.json\""
                 ${CMAKE_SOURCE_DIR}/scripts/compare_bui2008.py ${GRANFLOW_BUI_FIXTURE}_partial)
set_tests_properties(scripts_compare_bui2008_partial_run PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "failure_line_mean_distance_m = nan\n.*soil_outflow_fraction = 0[.]01\nenergy_budget_error = 0[.]0200\nwarning: the last output is at t = 2 s, before the case's time[.]end = 3 s[^\n]*\nwarning: the pile may still move at t = 2 s [(]the kinetic energy in the soil's mass is a root-mean-square speed of 0[.]0195 m/s[)][^\n]*\nwarning: 1 % of the soil left the domain.*\nnote: no failure line.*\"failure_line_mean_distance_m\": null"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:")
file(WRITE ${GRANFLOW_BUI_FIXTURE}_other/column_height_00001.csv
     "# soil height per column (sum of c dy) at t = 2 s\nx,height,x_east,floor_cell_height\n0.1,0.08,0.2,0.005\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}_other/surface_00001.csv "# surface at t = 2 s\nx0,y0,x1,y1\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}_other/failure_line_00001.csv "# failure_line at t = 2 s\nx0,y0,x1,y1\n")
file(WRITE ${GRANFLOW_BUI_FIXTURE}_other/history.csv "time,soil_volume,soil_outflow,kinetic_energy,potential_energy,dissipated_energy\n0.001,0.0065,0,0,1,0\n")
add_test(NAME scripts_compare_bui2008_one_cell_toe
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/compare_bui2008.py ${GRANFLOW_BUI_FIXTURE})
set_tests_properties(scripts_compare_bui2008_one_cell_toe PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "runout_one_cell_m = 0[.]3100\n.*energy_budget_error = 0[.]0200\n"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:;warning:")
add_test(NAME scripts_compare_bui2008_other_case
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/compare_bui2008.py ${GRANFLOW_BUI_FIXTURE}_other)
set_tests_properties(scripts_compare_bui2008_other_case PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*history.csv: the run's initial volume is 0.0065, not the 0.02 of the bui2008_experiment block")
# The stability plot's bracket from stability.csv: the factor of safety between the largest factor
# that stood and the smallest that failed; where every trial failed, the smallest tried (its mechanism
# is still the one to draw); where every trial stood, nothing to draw (status 1).
set(GRANFLOW_STABILITY_FIXTURE ${CMAKE_CURRENT_BINARY_DIR}/stability_fixture)
set(GRANFLOW_STABILITY_HEADER "factor,fails,diverged,largest_displacement_m,displacement_limit_m,time_s,steps,unconverged_steps,wall_seconds,directory")
file(WRITE ${GRANFLOW_STABILITY_FIXTURE}/bracket/stability.csv
     "${GRANFLOW_STABILITY_HEADER}\n1,0,0,0.001,0.01,1,100,0,1,F_1\n2,1,0,0.2,0.01,0.5,50,0,1,F_2\n1.5,0,0,0.002,0.01,1,100,0,1,F_1.5\n1.75,1,0,0.1,0.01,0.6,60,0,1,F_1.75\n")
file(WRITE ${GRANFLOW_STABILITY_FIXTURE}/fails/stability.csv
     "${GRANFLOW_STABILITY_HEADER}\n1,1,0,0.2,0.01,0.5,50,0,1,F_1\n0.5,1,0,0.1,0.01,0.6,60,0,1,F_0.5\n")
file(WRITE ${GRANFLOW_STABILITY_FIXTURE}/stands/stability.csv
     "${GRANFLOW_STABILITY_HEADER}\n1,0,0,0.001,0.01,1,100,0,1,F_1\n")
add_test(NAME scripts_plot_stability_bracket
         COMMAND sh -c "for k in bracket fails stands; do /usr/bin/python3 \"$0\" \"$1/$k\" 2>&1; echo \"status $?\"; done"
                 ${CMAKE_SOURCE_DIR}/scripts/plot_stability.py ${GRANFLOW_STABILITY_FIXTURE})
set_tests_properties(scripts_plot_stability_bracket PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^stands at F = 1[.]5000, fails at F = 1[.]7500: factor of safety 1[.]625\nstatus 0\nfails at every factor tried, down to F = 0[.]5000: factor of safety below it\nstatus 0\nerror: [^\n]*stands/stability.csv: the soil stands in every trial: no failure to draw\nstatus 1\n$")
# A reference line to draw over the mechanism must be a table of x and y.
file(WRITE ${GRANFLOW_STABILITY_FIXTURE}/line_of_r_z.csv "r,z\n0.5,1.5\n1.0,1.0\n")
add_test(NAME scripts_plot_stability_line_without_x_and_y
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/plot_stability.py
                 ${GRANFLOW_STABILITY_FIXTURE}/bracket --line ${GRANFLOW_STABILITY_FIXTURE}/line_of_r_z.csv)
set_tests_properties(scripts_plot_stability_line_without_x_and_y PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*line_of_r_z.csv: no rows of columns x, y\n$")
# The silo's discharge: a history draining at 0.02 m^2/s from the half silo (0.04 from the whole, slot
# 4 cm) is an hour-glass, Q ~ h^0 with Beverloo's coefficient 0.04 / (g^0.5 0.04^1.5) = 1.5964; a case
# without the silo's axis on its west side is refused.
set(GRANFLOW_SILO_FIXTURE ${CMAKE_CURRENT_BINARY_DIR}/silo_fixture)
set(GRANFLOW_SILO_CASE "title = \"silo\"\n[mesh]\nlower = [0.0, 0.0]\nupper = [0.15, 0.4]\n[physics]\ngravity = [0.0, -9.81]\n[boundary]\nwest = { type = \"symmetry\" }\n[[obstacle]]\nshape = \"box\"\nlower = [0.02, -0.01]\nupper = [0.16, 0.005]\n")
file(WRITE ${GRANFLOW_SILO_FIXTURE}/granflow_case.toml "${GRANFLOW_SILO_CASE}")
set(GRANFLOW_SILO_HISTORY "time,soil_volume,soil_outflow\n0,0.045,0\n0.05,0.044,0.001\n0.1,0.043,0.002\n0.15,0.042,0.003\n0.2,0.041,0.004\n0.25,0.04,0.005\n0.3,0.039,0.006\n0.35,0.038,0.007\n0.4,0.037,0.008\n0.45,0.036,0.009\n0.5,0.035,0.01\n0.55,0.034,0.011\n0.6,0.033,0.012\n0.65,0.032,0.013\n0.7,0.031,0.014\n0.75,0.03,0.015\n0.8,0.029,0.016\n0.85,0.028,0.017\n0.9,0.027,0.018\n0.95,0.026,0.019\n1,0.025,0.02\n")
file(WRITE ${GRANFLOW_SILO_FIXTURE}/history.csv "${GRANFLOW_SILO_HISTORY}")
string(REPLACE "symmetry" "wall" GRANFLOW_WALLED_CASE "${GRANFLOW_SILO_CASE}")
file(WRITE ${GRANFLOW_SILO_FIXTURE}_walled/granflow_case.toml "${GRANFLOW_WALLED_CASE}")
file(WRITE ${GRANFLOW_SILO_FIXTURE}_walled/history.csv "${GRANFLOW_SILO_HISTORY}")
add_test(NAME scripts_compare_silo_hour_glass
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/compare_silo.py ${GRANFLOW_SILO_FIXTURE})
set_tests_properties(scripts_compare_silo_hour_glass PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "slot L = 0[.]04 m, silo 0[.]3 m wide\n.*Q from 0[.]04 to 0[.]04 m\\^2/s [(]spread 0[.]00 %[)], Q ~ h\\^-?0[.]000 [(]hour-glass 0, clepsydra 0[.]5[)]. Beverloo.s coefficient 1[.]5964\n"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:")
add_test(NAME scripts_compare_silo_not_a_silo
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/compare_silo.py ${GRANFLOW_SILO_FIXTURE}_walled)
set_tests_properties(scripts_compare_silo_not_a_silo PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*silo_fixture_walled/granflow_case.toml: the west side is not the silo's axis [(]a symmetry plane[)]\n$")
# The SPH-case drawing refuses a run of another block too, rather than label it as the paper's figure.
add_test(NAME scripts_compare_bui2008_sph_other_case
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/compare_bui2008_sph.py ${GRANFLOW_BUI_FIXTURE}_other --times 2)
set_tests_properties(scripts_compare_bui2008_sph_other_case PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*history.csv: the run's initial volume is 0.0065, not the 8 of the 4 x 2 m block")
# The front's history interpolates between steps and marks times past the run's end.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/front_run/history.csv "time,dt,toe_contour\n0.0,0.1,0.2\n0.2,0.1,0.4\n")
add_test(NAME scripts_front_history
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/front_history.py ${CMAKE_CURRENT_BINARY_DIR}/front_run
                 --times 0.05,0.15,0.3)
set_tests_properties(scripts_front_history PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "front_run +0[.]250 +0[.]350 +-"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:")
# A restart with other materials is allowed, but said.
add_test(NAME cli_restart_other_physics_warned
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.03 --set soil.rheology.friction_angle=30 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_physics ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_other_physics_warned PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "warning: the case's physics [(][^)]*phi 30 deg[^)]*[)] differs from the checkpoint's run [(][^)]*phi 19.8 deg")
# ... and so is a restart with other boundaries.
add_test(NAME cli_restart_other_boundaries_warned
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; \"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.03 --set 'boundary.east={type = \"wall\"}' 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_boundaries ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_other_boundaries_warned PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "warning: the case.s boundaries [(][^)]*east wall [^)]*[)] differ from the checkpoint.s run [(][^)]*east atmosphere 0 Pa total"
                     FAIL_REGULAR_EXPRESSION "the case.s physics")
# A checkpoint written before the boundaries were recorded (no 'boundaries' line, nor the checksums
# after it) restarts the same case without a warning; one whose history rows have no soil_speed and
# boundary_work (written before those columns) gets NaN there, every row under its header.
add_test(NAME cli_restart_older_checkpoint_not_warned
         COMMAND sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; grep -q '^boundaries ' \"$d/checkpoint/run.txt\" && ! grep -qE '^physics .*(west|east|south|north) ' \"$d/checkpoint/run.txt\" || exit 1; sed -i '/^boundaries /d;/^boundary_work /d;/^checksum /d' \"$d/checkpoint/run.txt\"; sed -i -E '/^[-0-9.e+]+,/ s/^(([^,]*,){12})[^,]*,[^,]*,/\\1/' \"$d/checkpoint/run.txt\"; out=$(\"$g\" run \"$c\" -o \"$d\" --restart \"$@\" --set time.end=0.03 2>&1) || exit 1; ! echo \"$out\" | grep -q 'warning' && awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' \"$d/history.csv\" && sed -n 2p \"$d/history.csv\" | grep -q ',nan,nan,'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/restart_older ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_restart_older_checkpoint_not_warned PROPERTIES LABELS cli)
# The example of docs/case_file.md is a valid case, and runs.
add_test(NAME cli_docs_case_example
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "sed -n '/^## Example/,$p' \"$1\" | sed -n '/^```toml/,/^```$/p' | sed '1d;$d' > \"$2.toml\" && \"$0\" check \"$2.toml\" && \"$0\" run \"$2.toml\" -o \"$2\" --overwrite --set \"mesh.cells=[30,10]\" --set time.end=0.05 --set output.progress_seconds=0"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/docs/case_file.md ${CMAKE_CURRENT_BINARY_DIR}/docs_case_example)
set_tests_properties(cli_docs_case_example PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "done: t = 0.05 s"
                     FAIL_REGULAR_EXPRESSION "error:;warning:")
# A granular case with numerics that do not hold its pile at rest is valid, with a warning naming them.
add_test(NAME cli_check_advice_on_numerics
         COMMAND sh -c "out=$(\"$0\" check \"$1\" --set numerics.pressure_coupling=projection --set numerics.air_band=0 2>&1) && echo \"$out\" | grep -q ': valid (' && echo \"$out\" | grep -q 'warning: soil.rheology.regularisation = .exponential. with numerics.pressure_coupling = .projection.'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_check_advice_on_numerics PROPERTIES LABELS cli)
# Line samples end on the boundary's values: the cavity's vertical centre line starts at rest on the
# floor and ends on the lid's u = 1 (and v = 0).
add_test(NAME cli_line_sample_ends_on_the_walls
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "\"$0\" run \"$1\" -o \"$2\" --overwrite --set \"mesh.cells=[16,16]\" --set time.end=0.05 --set output.progress_seconds=0 > /dev/null && sed -n '3p;$p' \"$2/u_vertical_centreline.csv\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/line_sample)
set_tests_properties(cli_line_sample_ends_on_the_walls PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^0[.]5,0,0,0,[^\n]*\n0[.]5,1,1,0,")
# With soil, line samples add its fraction, strain norm and strain rate norm; on the floor (a wall)
# the velocity is zero.
add_test(NAME cli_line_sample_soil_columns
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "{ cat \"$1\"; printf '[[output.line]]\\nname = \"profile\"\\nstart = [0.1, 0.0]\\nend = [0.1, 0.05]\\npoints = 6\\n'; } > \"$2.toml\" && \"$0\" run \"$2.toml\" -o \"$2\" --overwrite --set \"mesh.cells=[30,10]\" --set time.end=0.05 --set output.fields=false --set output.progress_seconds=0 > /dev/null && sed -n '2,3p' \"$2/profile.csv\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/line_sample_soil)
set_tests_properties(cli_line_sample_soil_columns PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^x,y,u,v,p,viscosity,soil_fraction,strain_norm,strain_rate_norm\n0[.]1,0,0,0,[0-9.e+]+,[0-9.e+]+,1,")
# A linear solver that fails inside (hypre on a closed mesh of two cells) ends the run with one
# message, not PETSc's error trace.
add_test(NAME cli_linear_solver_failure_named
         COMMAND ${GRANFLOW_EXPECT_STATUS} 3 $<TARGET_FILE:granflow> run ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml -o ${CMAKE_CURRENT_BINARY_DIR}/solver_failure
                 --overwrite --set "mesh.cells=[1,2]" --set time.end=0.05 --set output.progress_seconds=0)
set_tests_properties(cli_linear_solver_failure_named PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: linear solver 'pressure' failed: [^\n]*another solver.pressure.pc_type may do"
                     FAIL_REGULAR_EXPRESSION "PETSC ERROR")
# A solve stopped at its iteration limit is accepted (the outer iterations may finish the job) but
# said: a warning at the first, and the count at the end.
add_test(NAME cli_linear_solver_iteration_limit_counted
         COMMAND sh -c "out=$(\"$0\" run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[16,16]' --set time.end=0.05 --set output.progress_seconds=0 --set solver.pressure.pc_type=none --set solver.pressure.max_iterations=1 2>&1) || exit 1; echo \"$out\" | grep -q \"warning: linear solver 'pressure' stopped at solver.pressure.max_iterations = 1\" && echo \"$out\" | grep -q 'warning: [1-9][0-9]* linear solves stopped at'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/iteration_limit)
set_tests_properties(cli_linear_solver_iteration_limit_counted PROPERTIES LABELS cli)
# Any other PETSc error is one line, not PETSc's trace (GRANFLOW_PETSC_TRACE=1 keeps the trace): here
# running out of memory while the grid is made (16 million cells within 1.5 GB of address space).
add_test(NAME cli_petsc_error_one_line
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "ulimit -v 1500000; exec \"$0\" run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[4000,4000]' --set time.end=0.01"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/petsc_error)
set_tests_properties(cli_petsc_error_one_line PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: PETSc: out of memory [(]a coarser mesh may do[)] [(]PETSc error [0-9]+ in PetscMallocAlign[^\n]*\n$"
                     FAIL_REGULAR_EXPRESSION "PETSC ERROR")
# A solver option PETSc refuses (an unknown method, a tolerance out of range) is bad input: one line and
# status 2, from `check` as from `run` before it starts. `check` reads the options without opening the
# files of monitors and viewers, which are the run's to write: monitor.txt keeps what it held.
add_test(NAME cli_petsc_solver_option_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\"; mkdir -p \"$d\"; echo kept > \"$d/monitor.txt\"; \"$g\" check \"$c\" \"--petsc=-pressure_ksp_monitor ascii:$d/monitor.txt -pressure_ksp_rtol 2\" 2>&1; test $? -eq 2 || exit 0; cat \"$d/monitor.txt\"; exec \"$g\" run \"$c\" -o \"$d/run\" --set 'mesh.cells=[8,8]' --set time.end=0.01 '--petsc=-pressure_ksp_type bogus'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/petsc_option_refused)
set_tests_properties(cli_petsc_solver_option_refused PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: linear solver 'pressure': rtol = 2 [(]solver.pressure.rtol, or PETSc's -pressure_ksp_rtol[)] must be within [[]0, 1[)]\nkept\nerror: linear solver 'pressure': PETSc refuses its options: Unable to find requested KSP type bogus\n$"
                     FAIL_REGULAR_EXPRESSION "PETSC ERROR")
# Conservative momentum transport needs the coupled solve: with the projection it is refused by name.
add_test(NAME cli_check_conservative_momentum_needs_coupled
         COMMAND sh -c "out=$(\"$0\" check \"$1\" --set numerics.momentum_transport=conservative 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'numerics.momentum_transport: .conservative. needs numerics.pressure_coupling = .coupled. (it is .projection.)'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/water_dam_break.toml)
set_tests_properties(cli_check_conservative_momentum_needs_coupled PROPERTIES LABELS cli)
# The run records the case as it took it (granflow_case.toml, with the --set assignments applied):
# run from that record, the case gives the same history to the bit.
add_test(NAME cli_case_record_runs_the_same_case
         COMMAND sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\" \"$d.again\"; \"$g\" run \"$c\" -o \"$d\" \"$@\" > /dev/null || exit 1; grep -q \"^#   --set 'mesh.cells=\\[20,20\\]'\" \"$d/granflow_case.toml\" || exit 1; \"$g\" run \"$d/granflow_case.toml\" -o \"$d.again\" > /dev/null || exit 1; cmp \"$d/history.csv\" \"$d.again/history.csv\""
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/case_record ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 ${GRANFLOW_SHORT_RUN})
set_tests_properties(cli_case_record_runs_the_same_case PROPERTIES LABELS cli)
# A case path that is not UTF-8 (Latin-1 "latin\351"): the record names it with \xNN, as TOML, which
# is UTF-8 throughout, can read back; run from that record, the case is valid.
add_test(NAME cli_case_record_of_a_path_not_utf8
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; d=$1; c=$2; rm -rf \"$d\"; mkdir -p \"$d\"; n=\"$d/$(printf 'lat\\351')\"; cp \"$c\" \"$n.toml\"; \"$g\" run \"$n.toml\" -o \"$d/run\" --set 'mesh.cells=[8,8]' --set time.end=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; head -1 \"$d/run/granflow_case.toml\" | sed 's/.*[/]//'; \"$g\" check \"$d/run/granflow_case.toml\" | sed 's/.*: valid .*/valid/'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/case_record_not_utf8 ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_case_record_of_a_path_not_utf8 PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "^lat\\\\xE9[.]toml\nvalid\n$")
add_test(NAME cli_version COMMAND ${GRANFLOW_EXPECT_STATUS} 0 $<TARGET_FILE:granflow> --version)
set_tests_properties(cli_version PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "^granflow [0-9]+[.][0-9]+[.][0-9]+\n$")
# granflow stability: a case with no strength to reduce is refused with one message; a soil that stands
# at every factor says so (status 1) and leaves its table; a second analysis into the directory is
# refused without --overwrite.
add_test(NAME cli_stability_needs_a_rheology
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> stability ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml -o ${CMAKE_CURRENT_BINARY_DIR}/stability_none)
set_tests_properties(cli_stability_needs_a_rheology PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*lid_driven_cavity_re100.toml: strength reduction needs soil with a rheology")
add_test(NAME cli_stability_refuses_mu_of_i
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> stability ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment_mu_of_i.toml -o ${CMAKE_CURRENT_BINARY_DIR}/stability_none)
set_tests_properties(cli_stability_refuses_mu_of_i PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "strength reduction divides a constant friction angle. mu[(]I[)] friction has none")
add_test(NAME cli_stability_stands_at_every_factor_and_keeps_its_analysis
         COMMAND sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\"; \"$g\" stability \"$c\" -o \"$d\" \"$@\" > /dev/null 2> \"$d.err\"; test $? -eq 1 && grep -q 'stands at every factor tried, up to F = 64' \"$d.err\" && test $(wc -l < \"$d/stability.csv\") -eq 8 && test -f \"$d/F_64/granflow_case.toml\" || exit 1; out=$(\"$g\" stability \"$c\" -o \"$d\" \"$@\" 2>&1); test $? -eq 2 && echo \"$out\" | grep -q 'holds an earlier analysis'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/stability_stands ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 --set "mesh.cells=[30,10]" --set time.end=0.02 --set soil.rheology.cohesion=1e5 --set output.progress_seconds=0 --set output.fields=false)
set_tests_properties(cli_stability_stands_at_every_factor_and_keeps_its_analysis PROPERTIES LABELS cli)
# A stability analysis where every factor fails names the case's numerics warned of above as a likely
# cause: an embankment on the projection and the cells' evaluations, set by hand, leaks at its sides.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/embankment_half.toml "[mesh]\ncells = [20, 12]\nupper = [10.0, 6.0]\n[time]\nend = 2.0\n[physics]\ngravity = [0.0, -9.81]\n[air]\ndensity = 1.2\nviscosity = 1.8e-5\n[soil]\ndensity = 1900.0\n[soil.rheology]\nfriction_angle = 30.0\ncohesion = 5000.0\n[[initial.soil]]\nshape = \"polygon\"\npoints = [[0.0, 0.0], [8.0, 0.0], [2.0, 4.0], [0.0, 4.0]]\n[boundary]\nwest = { type = \"symmetry\" }\neast = { type = \"atmosphere\" }\nsouth = { type = \"wall\" }\nnorth = { type = \"atmosphere\" }\n[output]\nprogress_seconds = 0\nfields = false\n")
add_test(NAME cli_stability_failing_everywhere_names_the_numerics_warned_of
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 $<TARGET_FILE:granflow> stability ${CMAKE_CURRENT_BINARY_DIR}/embankment_half.toml
                 -o ${CMAKE_CURRENT_BINARY_DIR}/stability_warned --overwrite --first 0.05 --tolerance 1 --displacement 0.02
                 --set numerics.pressure_coupling=projection --set soil.yield_pressure=cell)
set_tests_properties(cli_stability_failing_everywhere_names_the_numerics_warned_of PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "\nwarning: soil.rheology.regularisation = \"exponential\" with numerics.pressure_coupling = \"projection\"[^\n]*\n.*error: the soil fails at every factor tried, down to F = [^\n]*[(]mind the warnings on the case's numerics above: they may be why[)]\n")
# The command line's numbers are finite and in range: "nan" passes no comparison, and was taken.
add_test(NAME cli_stability_displacement_nan_refused
         COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> stability ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml --displacement nan)
set_tests_properties(cli_stability_displacement_nan_refused PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: --displacement: 'nan' is not a length from 1e-12 to 1e12 m [(]see granflow stability --help[)]\n")
add_test(NAME cli_element_test_phi_message COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> element-test --phi 0)
set_tests_properties(cli_element_test_phi_message PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: --phi: '0' is not an angle from 0.001 to 89.999 degrees [(]see granflow element-test --help[)]\n")
# An option given twice is said so, in words.
add_test(NAME cli_option_given_twice COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> element-test --phi 30 --phi 40)
set_tests_properties(cli_option_given_twice PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: --phi: given 2 times. give it once [(]see granflow element-test --help[)]\n$")
# Arguments a command does not take are named in the order given, with the command's own help.
add_test(NAME cli_check_takes_no_output COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> check ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml -o somewhere)
set_tests_properties(cli_check_takes_no_output PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: check does not take: -o somewhere. it writes no output directory [(]see granflow check --help[)]\n")
add_test(NAME cli_stability_first_nan_message COMMAND ${GRANFLOW_EXPECT_STATUS} 2 $<TARGET_FILE:granflow> stability ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml --first nan)
set_tests_properties(cli_stability_first_nan_message PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: --first: 'nan' is not a number from 0.01 to 100 [(]see granflow stability --help[)]\n")
# --overwrite keeps the earlier analysis while the new one fails before its first trial has ended: on an
# option PETSc refuses (read before the directory is touched), and where the first trial cannot make
# its directory (a file named F_3 stands there); then it replaces it.
add_test(NAME cli_stability_overwrite_keeps_the_analysis_until_the_first_trial_ends
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "g=$0; d=$1; c=$2; shift 2; rm -rf \"$d\" \"$d.kept\"; \"$g\" stability \"$c\" -o \"$d\" \"$@\" > /dev/null 2>&1; test $? -eq 1 || exit 1; cp \"$d/stability.csv\" \"$d.kept\"; \"$g\" stability \"$c\" -o \"$d\" --overwrite \"$@\" '--petsc=-coupled_ksp_type bogus' > /dev/null 2>&1 && exit 1; cmp -s \"$d/stability.csv\" \"$d.kept\" && test -f \"$d/F_64/granflow_case.toml\" || exit 1; touch \"$d/F_3\"; \"$g\" stability \"$c\" -o \"$d\" --overwrite --first 3 \"$@\" 2>&1; cmp -s \"$d/stability.csv\" \"$d.kept\" && test -f \"$d/F_64/granflow_case.toml\" && test ! -e \"$d/.replaced_run\" && echo kept; rm \"$d/F_3\"; \"$g\" stability \"$c\" -o \"$d\" --overwrite --first 2 \"$@\" > /dev/null 2>&1; test $? -eq 1 && test ! -e \"$d/F_1\" && test -f \"$d/F_2/granflow_case.toml\" && test ! -e \"$d/.replaced_run\" && echo replaced"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/stability_overwrite ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml
                 --set "mesh.cells=[30,10]" --set time.end=0.02 --set soil.rheology.cohesion=1e5 --set output.progress_seconds=0 --set output.fields=false)
set_tests_properties(cli_stability_overwrite_keeps_the_analysis_until_the_first_trial_ends PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "^granflow: factor of safety [^\n]*\nerror: -o [^\n]*stability_overwrite/F_3: cannot make the output directory: Not a directory\nkept\nreplaced\n$")
# A run that stops at its steady state marks its line samples so; the cavity comparison warns of a
# sample that is not one (a run stopped at time.end), and the chute's of a profile still changing.
add_test(NAME scripts_compare_cavity_steadiness
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "\"$0\" run \"$1\" -o \"$3/steady\" --overwrite --set 'mesh.cells=[16,16]' >/dev/null 2>&1 && head -1 \"$3/steady/u_vertical_centreline.csv\" && /usr/bin/python3 -u \"$2\" \"$3/steady\" 100 2>&1 && \"$0\" run \"$1\" -o \"$3/short\" --overwrite --set 'mesh.cells=[16,16]' --set time.end=0.5 >/dev/null 2>&1 && /usr/bin/python3 -u \"$2\" \"$3/short\" 100 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml
                 ${CMAKE_SOURCE_DIR}/scripts/compare_cavity.py ${CMAKE_CURRENT_BINARY_DIR}/cavity_steadiness)
set_tests_properties(scripts_compare_cavity_steadiness PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^# u_vertical_centreline at t = [0-9.]+ s, steady state reached\nRe 100: max [^\n]*\nwarning: [^\n]*short/u_vertical_centreline.csv is not a steady state [(]u_vertical_centreline at t = 0[.]5 s[)][^\n]*\nRe 100: max [^\n]*\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:")
add_test(NAME scripts_compare_bagnold_steadiness
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "\"$0\" run \"$1\" -o \"$3/short\" --overwrite --set time.end=1.5 >/dev/null 2>&1 && /usr/bin/python3 -u \"$2\" \"$3/short\" 2>&1 && \"$0\" run \"$1\" -o \"$3/full\" --overwrite >/dev/null 2>&1 && /usr/bin/python3 -u \"$2\" \"$3/full\" 2>&1 | sed 's/^/full: /'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bagnold_chute.toml
                 ${CMAKE_SOURCE_DIR}/scripts/compare_bagnold.py ${CMAKE_CURRENT_BINARY_DIR}/bagnold_steadiness)
set_tests_properties(scripts_compare_bagnold_steadiness PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "\nsteadiness = 0[.][1-4][0-9]+ [(]largest change of u from t = 1 to 1[.]5 s[^\n]*\nwarning: u changed by [1-4][0-9][.]?[0-9]* % [^\n]*[(]t = 1 and 1[.]5 s[)]: the flow is not yet steady\n.*\nfull: steadiness = 0[.]000[0-9]+ [(]largest change of u from t = 4[.]5 to 5 s"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:;steadiness = null;full: warning")
# A chute fed through an inlet starts without soil: the comparison takes each profile at its own depth for
# the inlet's flux and prints the depth the run reached (not yet steady at t = 1 s on 1 mm cells).
add_test(NAME scripts_compare_bagnold_inlet
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "\"$0\" run \"$1\" -o \"$3\" --overwrite --set 'mesh.cells=[100,15]' --set time.end=1.0 --set output.fields=false >/dev/null 2>&1 && /usr/bin/python3 -u \"$2\" \"$3\" 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/chute_inlet.toml
                 ${CMAKE_SOURCE_DIR}/scripts/compare_bagnold.py ${CMAKE_CURRENT_BINARY_DIR}/bagnold_inlet)
set_tests_properties(scripts_compare_bagnold_inlet PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "\nflux_m2_s = 0[.]001854\ndepth_for_flux_bagnold_m = 0[.]00999[67][0-9]*\ndepth_for_flux_model_m = 0[.]0100[0-9]+\ndepth_computed_m = 0[.]00[89][0-9]+ [(]the sample's soil fraction times its spacing[)]\n.*\nwarning: u changed by [^\n]*the flow is not yet steady"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:;steadiness = null")
# The energy budget over a window: the gains, the dissipation and the energy brought in through the
# sides, and the residual as a share of the potential energy released and of what was brought in; a
# window beyond the run, and a history of before boundary_work, are refused.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/budget_run/history.csv
     "time,dt,kinetic_energy,potential_energy,dissipated_energy,boundary_work\n0.0,0.1,0.0,10.0,0.0,0.0\n"
     "1.0,0.1,1.0,6.0,2.0,-1.0\n2.0,0.1,1.0,2.0,3.5,-3.0\n")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/budget_old/history.csv
     "time,dt,kinetic_energy,potential_energy,dissipated_energy\n0.0,0.1,0.0,10.0,0.0\n1.0,0.1,1.0,6.0,2.0\n")
add_test(NAME scripts_energy_budget
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/energy_budget.py
                 ${CMAKE_CURRENT_BINARY_DIR}/budget_run)
set_tests_properties(scripts_energy_budget PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "budget_run: t = 0 to 2 s\n  kinetic energy gained +1\n  potential energy gained +-8\n  dissipated +3[.]5\n  brought in through sides +-3\n  residual [(]gained [+] dissipated - brought in[)] -0[.]5: -6[.]2500% of the potential energy released, [+]16[.]6667% of the energy brought in\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:")
add_test(NAME scripts_energy_budget_window
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 /usr/bin/python3 ${CMAKE_SOURCE_DIR}/scripts/energy_budget.py
                 ${CMAKE_CURRENT_BINARY_DIR}/budget_run --from 0.5 --to 1.5)
set_tests_properties(scripts_energy_budget_window PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "t = 0[.]5 to 1[.]5 s\n  kinetic energy gained +0[.]5\n  potential energy gained +-4\n  dissipated +1[.]75\n  brought in through sides +-1[.]5\n  residual [^\n]* -0[.]25: -6[.]2500% of the potential energy released, [+]16[.]6667% of the energy brought in\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback;error:")
add_test(NAME scripts_energy_budget_refusals
         COMMAND ${GRANFLOW_EXPECT_STATUS} 1 sh -c "/usr/bin/python3 \"$0\" \"$1\" --to 3 2>&1; /usr/bin/python3 \"$0\" \"$2\" 2>&1; exit 1"
                 ${CMAKE_SOURCE_DIR}/scripts/energy_budget.py ${CMAKE_CURRENT_BINARY_DIR}/budget_run
                 ${CMAKE_CURRENT_BINARY_DIR}/budget_old)
set_tests_properties(scripts_energy_budget_refusals PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: the window 0 to 3 s is not within the run's 0 to 2 s, from an earlier time to a later one\nerror: [^\n]*budget_old/history.csv: no column boundary_work [(]written by an earlier granflow. run the case again[)]\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback")
# The axisymmetric comparison scores each run it finds and skips, with a note, a run that did not
# start with its case's soil (here a cylinder of half the radius under lube2004_a05's name).
add_test(NAME scripts_compare_axisymmetric_skips_another_block
         COMMAND ${GRANFLOW_EXPECT_STATUS} 0 sh -c "\"$0\" run \"$1/lube2004_a2.toml\" -o \"$3/lube2004_a2_drucker_prager\" --overwrite --set 'mesh.cells=[36,18]' --set time.end=0.1 >/dev/null 2>&1 && \"$0\" run \"$1/lube2004_a05.toml\" -o \"$3/lube2004_a05_mohr_coulomb\" --overwrite --set 'mesh.cells=[36,18]' --set time.end=0.1 --set 'initial.soil=[{shape=\"box\",lower=[0,0],upper=[0.1,0.1]}]' >/dev/null 2>&1 && /usr/bin/python3 -u \"$2\" \"$3\" 2>&1"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases ${CMAKE_SOURCE_DIR}/scripts/compare_axisymmetric.py
                 ${CMAKE_CURRENT_BINARY_DIR}/axisymmetric_runs)
set_tests_properties(scripts_compare_axisymmetric_skips_another_block PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "note: [^\n]*lube2004_a05_mohr_coulomb: skipped [(]InputError: [^\n]*the run's initial volume is 0[.]000498[0-9]*, not the 0[.]002 of the cylinder a = 0[.]5 of lube2004_a05[.]toml[^\n]*\n.*\nlube2004_a2 +drucker_prager +0[.]1 +0[.]12[0-9]+ "
                     FAIL_REGULAR_EXPRESSION "Traceback;error:")
# Any field of a run to PNG: the outputs and fields listed, the output nearest a time, a log scale over
# the soil; a misspelt field named with the run's fields, and no picture written.
add_test(NAME scripts_plot_field
         COMMAND sh -c "g=$0; p=$1; c=$2; d=$3; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[30,10]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; /usr/bin/python3 \"$p\" \"$d\" --time 0.012; /usr/bin/python3 \"$p\" \"$d\" --field viscosity --log --soil-only --png \"$d/v.png\" && test -s \"$d/v.png\" && echo drawn; /usr/bin/python3 \"$p\" \"$d\" --field velocty --png \"$d/x.png\" 2>&1; echo \"status $?\"; test ! -e \"$d/x.png\" && echo 'none written'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/scripts/plot_field.py ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/plot_field_run)
set_tests_properties(scripts_plot_field PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^3 outputs: 0 [(]t = 0 s[)], 1 [(]t = 0[.]01 s[)], 2 [(]t = 0[.]02 s[)]\nfields of output 1: density, displacement [(]3 components[)], [^\n]*, viscosity\nwrote [^\n]*v[.]png [(]log10 viscosity [(]Pa s[)] from [^\n]*[)]\ndrawn\nerror: [^\n]*has no field velocty. it has [^\n]*velocity[^\n]*\nstatus 1\nnone written\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback")
# A time outside the run's outputs is refused, not taken as the first or last output.
add_test(NAME scripts_plot_field_time_outside_the_outputs
         COMMAND sh -c "g=$0; p=$1; c=$2; d=$3; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[30,10]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; /usr/bin/python3 \"$p\" \"$d\" --time -5 --field pressure --png \"$d/p.png\" 2>&1; echo \"status $?\"; test ! -e \"$d/p.png\" && echo 'none written'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/scripts/plot_field.py ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/plot_field_time)
set_tests_properties(scripts_plot_field_time_outside_the_outputs PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: --time -5: the run's outputs lie from t = 0 to 0[.]02 s\nstatus 1\nnone written\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback")
# A case with obstacles is drawn (its blocked cells left out of the colour scale); on a log scale the air
# at rest does not set the scale's floor (at most 14 decades below the largest); a component asked of a
# scalar field is refused rather than ignored.
add_test(NAME scripts_plot_field_obstacles_and_components
         COMMAND sh -c "g=$0; p=$1; c=$2; d=$3; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[120,40]' --set time.end=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; /usr/bin/python3 \"$p\" \"$d\" --field velocity --component x --png \"$d/u.png\" && test -s \"$d/u.png\" && echo drawn; /usr/bin/python3 \"$p\" \"$d\" --field velocity --component x --log --png \"$d/ul.png\" 2>/dev/null; /usr/bin/python3 \"$p\" \"$d\" --field pressure --component y --png \"$d/p.png\" 2>&1; echo \"status $?\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/scripts/plot_field.py ${CMAKE_SOURCE_DIR}/cases/barrier_collapse.toml ${CMAKE_CURRENT_BINARY_DIR}/plot_field_obstacles)
set_tests_properties(scripts_plot_field_obstacles_and_components PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^wrote [^\n]*u[.]png [(]velocity x [(]m/s[)] from [^\n]*\ndrawn\nwrote [^\n]*ul[.]png [(]log10 velocity x [(]m/s[)] from -[0-9]?[0-9][.][0-9]+ to [^\n]*\nerror: --component y: pressure is a scalar field. --component is for vector fields\nstatus 1\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback")

# A case file named so that out/NAME would be out/ itself or its parent ("..toml", "...toml") is
# refused without -o, before anything is written.
file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/dots)
file(COPY_FILE ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/dots/...toml)
add_test(NAME cli_default_output_directory_stays_under_out
         COMMAND sh -c "cd \"$1\" && out=$($0 run ...toml --set 'mesh.cells=[8,8]' 2>&1); status=$?; echo \"$out\"; test $status -eq 2 && echo \"$out\" | grep -q '^error: [.][.][.]toml: the case file.s name gives no directory under out/' && test ! -e out && ! ls | grep -q fields"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/dots)
set_tests_properties(cli_default_output_directory_stays_under_out PROPERTIES LABELS cli)

# A factorisation that runs out of memory (here under an 800 MB address-space limit) is said as such,
# with status 1 and no retried steps, not as a linear solver that failed (DIVERGED_PC_FAILED, status 3).
add_test(NAME cli_factorisation_out_of_memory
         COMMAND sh -c "ulimit -v 800000 && out=$($0 run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[500,500]' --set time.end=0.01 2>&1); status=$?; echo \"$out\"; test $status -eq 1 && echo \"$out\" | grep -q \"^error: linear solver 'coupled': out of memory in its factorisation\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/out_of_memory)
set_tests_properties(cli_factorisation_out_of_memory PROPERTIES LABELS cli TIMEOUT 120)

# A strength reduction whose every trial diverges (here under an absurd gravity) says that the solution
# broke down, with the first trial's divergence, and status 3; not that the soil cannot stand.
add_test(NAME cli_stability_every_trial_diverged
         COMMAND sh -c "out=$($0 stability \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[30,10]' --set 'physics.gravity=[0,-1e30]' 2>&1); status=$?; echo \"$out\"; test $status -eq 3 && echo \"$out\" | grep -q '^error: every trial diverged, down to F = .*the first trial, F = 1: the solution diverged at .*largest speed NaN m/s'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/every_trial_diverged)
set_tests_properties(cli_stability_every_trial_diverged PROPERTIES LABELS cli TIMEOUT 120)

# PETSc's memory tracing (-malloc_debug, -malloc_dump) finds no corrupted block and no leak: the error
# handler pushed before PETSc starts is not freed by PETSc's tracing allocator afterwards.
add_test(NAME cli_petsc_memory_tracing_is_clean
         COMMAND $<TARGET_FILE:granflow> run ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml -o ${CMAKE_CURRENT_BINARY_DIR}/malloc_debug
                 --overwrite --set "mesh.cells=[30,10]" --set time.end=0.01 --set output.progress_seconds=0 "--petsc=-malloc_debug -malloc_dump")
set_tests_properties(cli_petsc_memory_tracing_is_clean PROPERTIES LABELS cli TIMEOUT 120
                     FAIL_REGULAR_EXPRESSION "PETSC ERROR;\\[ *[0-9]+\\] [0-9]+ bytes")

# A factorisation that PETSc's options ask for and PETSc would accept but could not carry out is bad
# input found by check: a Cholesky factor of the coupled system (which the case file refuses as
# pc_type), a factorisation package this PETSc does not have, an ILU asked of MUMPS (the package the
# case's lu sets).
add_test(NAME cli_check_petsc_factorisation_it_cannot_do
         COMMAND sh -c "a=$($0 check \"$1\" '--petsc=-coupled_pc_type cholesky' 2>&1); sa=$?; b=$($0 check \"$1\" '--petsc=-coupled_pc_factor_mat_solver_type nosuch' 2>&1); sb=$?; c=$($0 check \"$1\" '--petsc=-coupled_pc_type ilu' 2>&1); sc=$?; echo \"$a\"; echo \"$b\"; echo \"$c\"; test $sa -eq 2 && test $sb -eq 2 && test $sc -eq 2 && echo \"$c\" | grep -q \"^error: linear solver 'coupled': its factorisation package 'mumps' does not do pc_type 'ilu'\" && echo \"$a\" | grep -q \"^error: linear solver 'coupled': PETSc's options make its pc_type 'cholesky', which needs a symmetric\" && echo \"$b\" | grep -q \"^error: linear solver 'coupled': PETSc's options name the factorisation package 'nosuch', which this PETSc does not have\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_check_petsc_factorisation_it_cannot_do PROPERTIES LABELS cli)

# A restart whose case adds soil materials the checkpoint's run did not have is told so, by name, not as
# a checkpoint of other numerics with two lists of fields.
add_test(NAME cli_restart_with_other_soil_materials
         COMMAND sh -c "$0 run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[30,10]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; out=$($0 run \"$1\" -o \"$2\" --restart --set 'mesh.cells=[30,10]' --set time.end=0.03 --set 'soil.materials=[{name=\"clay\", friction_angle=25}]' --set 'initial.soil=[{shape=\"box\", lower=[0,0], upper=[0.2,0.1], material=\"clay\"}]' 2>&1); status=$?; echo \"$out\"; test $status -eq 1 && echo \"$out\" | grep -q '^error: the checkpoint.s run had other soil materials (none besides the rheology.s soil) than the case has (clay)'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/restart_materials)
set_tests_properties(cli_restart_with_other_soil_materials PROPERTIES LABELS cli TIMEOUT 120)

# A strength reduction killed midway keeps the table of the trials it finished: stability.csv is
# written after each trial (here killed once it has said two trials, of some nine; the rows are the
# trials it said it finished, or one more if the kill fell between the table and the line).
add_test(NAME cli_stability_killed_keeps_its_table
         COMMAND sh -c "rm -rf \"$2\"; $0 stability \"$1\" -o \"$2\" --set 'mesh.cells=[40,10]' --set time.end=5 --set output.progress_seconds=0 > \"$2.log\" 2>&1 & pid=$!; k=0; while test $(grep -c '^F = ' \"$2.log\") -lt 2 && kill -0 $pid 2>/dev/null && test $k -lt 500; do sleep 0.1; k=$((k + 1)); done; kill -KILL $pid; wait $pid; n=$(grep -c '^F = ' \"$2.log\"); r=$(($(wc -l < \"$2/stability.csv\") - 1)); echo \"$n trials said, $r rows\"; test $n -ge 2 && test $r -ge $n && test $r -le $((n + 1)) && ! grep -q '^factor of safety' \"$2.log\""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/slope_griffiths_lane1999.toml ${CMAKE_CURRENT_BINARY_DIR}/stability_killed)
set_tests_properties(cli_stability_killed_keeps_its_table PROPERTIES LABELS cli TIMEOUT 60)

# A linear solve that diverges (here a pressure solve by an over-relaxed Richardson iteration, whose
# residual grows) is taken again with a shorter step when the step is adaptive, and the run ends; with
# a fixed step it stops with the time, step and solver named, status 3.
set(GRANFLOW_DIVERGING_PRESSURE_SOLVE "--petsc=-pressure_ksp_type richardson -pressure_ksp_richardson_scale 1000 -pressure_pc_type none")
add_test(NAME cli_diverged_linear_solve_takes_the_step_again
         COMMAND sh -c "out=$($0 run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[16,16]' --set time.end=0.02 --set output.progress_seconds=0 \"$3\" 2>&1); status=$?; echo \"$out\"; test $status -eq 0 && echo \"$out\" | grep -qE '^done: t = 0.02 s in [0-9]+ steps \\([1-9][0-9]* taken again'; a=$?; out=$($0 run \"$1\" -o \"$2\" --overwrite --set 'mesh.cells=[16,16]' --set time.end=0.02 --set time.adaptive=false \"$3\" 2>&1); status=$?; echo \"$out\"; test $a -eq 0 && test $status -eq 3 && echo \"$out\" | grep -q \"^error: at t = 0 s (step 1, dt = 0.01 s): linear solver 'pressure' failed: DIVERGED_DTOL; \""
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml ${CMAKE_CURRENT_BINARY_DIR}/diverged_linear_solve
                 ${GRANFLOW_DIVERGING_PRESSURE_SOLVE})
set_tests_properties(cli_diverged_linear_solve_takes_the_step_again PROPERTIES LABELS cli TIMEOUT 120)

# The scripts refuse what they cannot read or write with one line, never a traceback: a fields file cut
# short, --json onto a run's own file (it would replace history.csv), a picture of a kind not drawn.
add_test(NAME scripts_refuse_damaged_files_and_bad_names
         COMMAND sh -c "g=$0; s=$1; c=$2; d=$3; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set 'mesh.cells=[30,10]' --set time.end=0.02 --set output.interval=0.01 --set output.progress_seconds=0 > /dev/null || exit 1; head -c 3000 \"$d/fields_00002.vtr\" > \"$d/cut.vtr\" && mv \"$d/cut.vtr\" \"$d/fields_00002.vtr\"; /usr/bin/python3 \"$s/plot_field.py\" \"$d\" --field viscosity --png \"$d/v.png\" 2>&1; echo \"status $?\"; cp \"$d/history.csv\" \"$d/kept.csv\"; /usr/bin/python3 \"$s/compare_bui2008.py\" \"$d\" --json \"$d/history.csv\" 2>&1; echo \"status $?\"; cmp -s \"$d/history.csv\" \"$d/kept.csv\" && echo kept; /usr/bin/python3 \"$s/plot_field.py\" \"$d\" --png \"$d/x.xyz\" 2>&1 | tail -1; test ! -e \"$d/v.png\" && test ! -e \"$d/x.xyz\" && echo 'none written'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/scripts ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml ${CMAKE_CURRENT_BINARY_DIR}/scripts_damaged)
set_tests_properties(scripts_refuse_damaged_files_and_bad_names PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "^error: [^\n]*fields_00002[.]vtr: not a whole fields file [(]damaged, or cut short[)]\nstatus 1\nusage: [^\n]*\n[^\n]*argument --json: [^\n]*the numbers go to a file ending in [.]json\nstatus 2\nkept\n[^\n]*argument --png: [^\n]*a picture ends in [.]png, [.]pdf, [.]svg\nnone written\n$"
                     FAIL_REGULAR_EXPRESSION "Traceback")

# granflow stability --restart continues an analysis stopped midway to the factor and trials of one run
# through, runs an unfinished trial again, and refuses another case or displacement limit.
add_test(NAME cli_stability_restart_continues_the_search
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/stability_restart.sh $<TARGET_FILE:granflow>
                 ${CMAKE_SOURCE_DIR}/cases/slope_griffiths_lane1999.toml ${CMAKE_CURRENT_BINARY_DIR}/stability_restart)
set_tests_properties(cli_stability_restart_continues_the_search PROPERTIES LABELS cli TIMEOUT 300)

# A mesh of layers from the case file: the 3D column runs a few steps and writes its fields with three
# components and z extents, a history with the forces on its six sides, and its surface as a height map
# over (x, z); granflow check states its cells and soil volume in m^3; its checkpoint takes --restart
# on to a later end.
add_test(NAME cli_run_a_mesh_of_layers
         COMMAND sh -c "g=$0; c=$1; d=$2; rm -rf \"$d\"; \"$g\" check \"$c\" | grep -q '(40 x 16 x 40 cells, t_end = 0.5 s. initial soil 0.00314156 m^3)' || exit 1; \"$g\" run \"$c\" -o \"$d\" --set time.end=0.01 --set 'output.times=[0.005]' --set output.progress_seconds=0 > \"$d.log\" 2>&1 || { cat \"$d.log\"; exit 1; }; grep -q 'on 40 x 16 x 40 cells' \"$d.log\" && grep -q 'WholeExtent=\"0 40 0 16 0 40\"' \"$d/fields_00001.vtr\" && head -1 \"$d/history.csv\" | grep -q ',soil_speed,boundary_work,force_west_x,force_west_y,force_west_z,.*,force_back_z$' && test $(grep -c . \"$d/column_height_00002.csv\") -eq 1602 && sed -n 2p \"$d/column_height_00002.csv\" | grep -q '^x,z,height$' && test -s \"$d/checkpoint/fields.bin\" && \"$g\" run \"$c\" -o \"$d\" --restart --set time.end=0.015 --set 'output.times=[0.005]' --set output.progress_seconds=0 > \"$d.restart.log\" 2>&1 && grep -q 'done: t = 0.015 s' \"$d.restart.log\" && tail -1 \"$d/history.csv\" | grep -q '^0.015,'"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/lube2004_a05_3d.toml ${CMAKE_CURRENT_BINARY_DIR}/layers_run)
set_tests_properties(cli_run_a_mesh_of_layers PROPERTIES LABELS cli TIMEOUT 300)
# Obstacles on a mesh of layers from the case file: the slit barrier's run writes the barrier's force
# along x, y and z and each column's blocked height beside its soil height; plot_height_map.py sums the
# soil, the share beyond the barrier, and draws the height map with the barrier's footprint. A line
# sample through the barrier has three coordinates and w, no values inside it and the wall's velocity
# on its face.
add_test(NAME cli_run_obstacles_of_layers_and_plot_their_height_map
         COMMAND sh -c "g=$0; c=$1; p=$2; d=$3; rm -rf \"$d\"; \"$g\" run \"$c\" -o \"$d\" --set time.end=0.01 --set 'output.times=[0.01]' --set output.fields=false --set output.progress_seconds=0 --set \"output.line=[{name='across', start=[0.3,0.015,0.05], end=[0.5,0.015,0.05], points=21}]\" > \"$d.log\" 2>&1 || { cat \"$d.log\"; exit 1; }; head -1 \"$d/history.csv\" | grep -q ',force_back_z,force_obstacle_x,force_obstacle_y,force_obstacle_z$' && sed -n 2p \"$d/across.csv\" | grep -q '^x,y,z,u,v,w,p,viscosity,soil_fraction,' && grep -q '^0.41,0.015,0.05,nan,nan,nan,nan,' \"$d/across.csv\" && grep -q '^0.4,0.015,0.05,0,0,0,[0-9]' \"$d/across.csv\" && sed -n 2p \"$d/column_height_00001.csv\" | grep -q '^x,z,height,obstacle_height$' && grep -q '^0.415,0.095,0,0.03$' \"$d/column_height_00001.csv\" && grep -q '^0.415,0.025,0,0$' \"$d/column_height_00001.csv\" && out=$(/usr/bin/python3 \"$p\" \"$d\" --beyond 0.42 --png \"$d/map.png\") && echo \"$out\" | grep -q '^t = 0.01 s: soil volume 0.002 m^3, highest column 0.1000 m, 0.00 % of it beyond x = 0.42 m$' && test -s \"$d/map.png\" || { echo \"$out\"; exit 1; }"
                 $<TARGET_FILE:granflow> ${CMAKE_SOURCE_DIR}/cases/slit_barrier_3d.toml ${CMAKE_SOURCE_DIR}/scripts/plot_height_map.py
                 ${CMAKE_CURRENT_BINARY_DIR}/slit_barrier_run)
set_tests_properties(cli_run_obstacles_of_layers_and_plot_their_height_map PROPERTIES LABELS cli TIMEOUT 300)
# A collapse in a narrow channel between walls of their own friction (10 deg): in the history each side
# wall carries a shear along x no more than tan(10 deg) = 0.1763 times its normal force, the same on
# both walls (their normal forces opposed).
add_test(NAME cli_run_a_narrow_channel_between_walls_of_their_own_friction
         COMMAND sh -c "d=$1; rm -rf \"$d\"; \"$0\" run \"$2\" -o \"$d\" --set time.end=0.05 --set output.fields=false --set output.progress_seconds=0 > \"$d.log\" 2>&1 || { cat \"$d.log\"; exit 1; }; head -1 \"$d/history.csv\" | cut -d, -f27-32 | grep -qx 'force_front_x,force_front_y,force_front_z,force_back_x,force_back_y,force_back_z' && tail -1 \"$d/history.csv\" | awk -F, '{ r = $27 / -$29; print \"front wall shear / normal force\", r; exit !($27 > 0.5 && r > 0.03 && r <= 0.1764 && ($27 - $30) < 1e-4 * $27 && ($30 - $27) < 1e-4 * $27 && ($29 + $32) < 1e-4 * $32 && -($29 + $32) < 1e-4 * $32) }'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/narrow_channel_run ${CMAKE_SOURCE_DIR}/cases/narrow_channel_3d.toml)
set_tests_properties(cli_run_a_narrow_channel_between_walls_of_their_own_friction PROPERTIES LABELS cli TIMEOUT 300)
# Soil materials on a mesh of layers: check says each one's soil, the fields hold each one's volume
# fraction, and a restart ends where a run straight through does (tests/materials_of_layers.sh).
add_test(NAME cli_soil_materials_of_layers
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/materials_of_layers.sh $<TARGET_FILE:granflow>
                 ${CMAKE_SOURCE_DIR}/cases/narrow_channel_3d.toml ${CMAKE_CURRENT_BINARY_DIR}/materials_of_layers)
set_tests_properties(cli_soil_materials_of_layers PROPERTIES LABELS cli TIMEOUT 300)
# Line samples on a mesh of layers: a layer-independent water column's samples at any depth are the
# planar run's (tests/line_samples_of_layers.sh).
add_test(NAME cli_line_samples_of_layers_are_the_planar_ones
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/line_samples_of_layers.sh $<TARGET_FILE:granflow>
                 ${CMAKE_SOURCE_DIR}/cases/water_dam_break.toml ${CMAKE_CURRENT_BINARY_DIR}/line_samples_of_layers)
set_tests_properties(cli_line_samples_of_layers_are_the_planar_ones PROPERTIES LABELS cli TIMEOUT 300)
