# tests/plc_blocks tests whose fixtures fracdesign makes at build time
# (included by tests/CMakeLists.txt). Without fracdesign (FRAC_C_ONLY, e.g.
# the sanitizer build of make check) these tests are not built.
#
# test_armctrl_flexarm: ArmCtrl's parameter tables of seed 004 Exp. A-D
# (`fracdesign armctrl`, the HIL bench's tables of hil_tables) and the full-order flexible arm as a plant table
# (`fracdesign model arm --full --save-plant`, N = 12 collocation points,
# exact ZOH at the 100 us system tick, beam damping r_t = 0.5 as the
# design's).
set(PLC_FRACDESIGN_TESTS ${CMAKE_CURRENT_LIST_DIR}/test_armctrl_flexarm.c)
if(NOT TARGET fracdesign)
  list(REMOVE_ITEM PLC_TESTS ${PLC_FRACDESIGN_TESTS})
endif()

function(plc_fracdesign_fixtures)
  if(NOT TARGET fracdesign OR NOT TARGET test_armctrl_flexarm)
    return()
  endif()
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/plc_fixtures)
  add_custom_command(OUTPUT ${dir}/arm_plant.bin
    COMMAND ${CMAKE_COMMAND} -E make_directory ${dir}
    COMMAND fracdesign model arm --N 12 --full --r_t 0.5 --h 1e-4 --save-plant ${dir}/arm_plant.bin
    DEPENDS fracdesign
    COMMENT "fracdesign model arm --save-plant (test_armctrl_flexarm fixture)"
    VERBATIM)
  add_custom_target(plc_flexarm_fixtures DEPENDS ${dir}/arm_plant.bin)
  # the ArmCtrl tables are the bench's (hil/CMakeLists.txt, hil_tables)
  add_dependencies(test_armctrl_flexarm plc_flexarm_fixtures hil_tables)
  target_compile_definitions(test_armctrl_flexarm PRIVATE FLEXARM_FIXTURE_DIR="${dir}"
    FLEXARM_TABLE_DIR="${PROJECT_BINARY_DIR}/hil/tables")
endfunction()
