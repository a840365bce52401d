# The command line: bad input gets one clear message and a non-zero exit.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/misspelt.toml "[mesh]\ncells = [4, 4]\nupper = [1.0, 1.0]\nupeer = 3\n")
add_test(NAME cli_check_misspelt_key COMMAND granflow check ${CMAKE_CURRENT_BINARY_DIR}/misspelt.toml)
set_tests_properties(cli_check_misspelt_key PROPERTIES LABELS cli WILL_FAIL TRUE)
add_test(NAME cli_check_misspelt_key_message COMMAND granflow check ${CMAKE_CURRENT_BINARY_DIR}/misspelt.toml)
set_tests_properties(cli_check_misspelt_key_message PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: mesh.upeer: unknown key")
add_test(NAME cli_run_missing_file COMMAND granflow run ${CMAKE_CURRENT_BINARY_DIR}/no_such_case.toml)
set_tests_properties(cli_run_missing_file PROPERTIES LABELS cli WILL_FAIL TRUE)
add_test(NAME cli_restart_without_checkpoint
         COMMAND granflow run ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml
                 -o ${CMAKE_CURRENT_BINARY_DIR}/no_such_run --restart)
set_tests_properties(cli_restart_without_checkpoint PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "error: no checkpoint to restart from")
# ... and leaves no output directory behind where there was none.
add_test(NAME cli_failed_restart_leaves_no_directory
         COMMAND sh -c "rm -rf \"$1\"; out=$(\"$0\" run \"$2\" -o \"$1\" --restart 2>&1); test $? -ne 0 && test ! -e \"$1\" && echo \"$out\" | grep -q 'no checkpoint to restart from .*: no such directory'"
                 $<TARGET_FILE:granflow> ${CMAKE_CURRENT_BINARY_DIR}/no_such_run_left
                 ${CMAKE_SOURCE_DIR}/cases/lid_driven_cavity_re100.toml)
set_tests_properties(cli_failed_restart_leaves_no_directory PROPERTIES LABELS cli)
add_test(NAME cli_check_shipped_cases COMMAND granflow check ${CMAKE_SOURCE_DIR}/cases/bui2008_experiment.toml)
set_tests_properties(cli_check_shipped_cases PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "valid")
add_test(NAME cli_element_test_csv COMMAND granflow element-test --csv)
set_tests_properties(cli_element_test_csv PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "deformation,theta_deg,model,eta_norm_D_over_p,norm_Tdev_over_p,relative")
# Every shipped case file validates.
file(GLOB GRANFLOW_SHIPPED_CASES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/cases/*.toml)
foreach(case_file ${GRANFLOW_SHIPPED_CASES})
  get_filename_component(case_name ${case_file} NAME_WE)
  add_test(NAME cli_check_case_${case_name} COMMAND granflow check ${case_file})
  set_tests_properties(cli_check_case_${case_name} PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION ": valid [(]")
endforeach()
