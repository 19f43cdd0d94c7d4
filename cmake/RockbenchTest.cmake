# rockbench_test(NAME SOURCES... [LIBS libs...] [TIMEOUT s] [PROGRAM]): one GoogleTest program,
# its tests discovered into CTest. PROGRAM: it runs the rockbench program (ROCKBENCH_EXE).
# Every test program sees ROCKBENCH_SOURCE_DIR and tests/ (the shared test headers).
include(GoogleTest)
function(rockbench_test name)
  cmake_parse_arguments(T "PROGRAM" "TIMEOUT" "LIBS" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  add_executable(${name} ${T_UNPARSED_ARGUMENTS})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests ${PROJECT_SOURCE_DIR}/src)
  target_compile_definitions(${name} PRIVATE ROCKBENCH_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  if(T_PROGRAM)
    target_compile_definitions(${name} PRIVATE ROCKBENCH_EXE="$<TARGET_FILE:rockbench>")
    add_dependencies(${name} rockbench)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${T_TIMEOUT})
endfunction()
