# The random pipeline-and-shader generator (tests/gen), a static library
# shared by the ctest property test (tests/gen/CMakeLists.txt) and
# bench/generate-and-check (bench/CMakeLists.txt). Included from both, so
# it is defined once whichever of SPIRE_BUILD_TESTS / SPIRE_BUILD_BENCH is on.
if(NOT TARGET spire_test_generator)
  add_library(spire_test_generator STATIC
    ${CMAKE_CURRENT_LIST_DIR}/campaign.cpp
    ${CMAKE_CURRENT_LIST_DIR}/decision_generator.cpp
    ${CMAKE_CURRENT_LIST_DIR}/expression_generator.cpp
    ${CMAKE_CURRENT_LIST_DIR}/interface_check.cpp
    ${CMAKE_CURRENT_LIST_DIR}/pipeline_generator.cpp
    ${CMAKE_CURRENT_LIST_DIR}/program_generator.cpp
    ${CMAKE_CURRENT_LIST_DIR}/value_type.cpp
    ${CMAKE_CURRENT_LIST_DIR}/variant_checker.cpp)
  target_include_directories(spire_test_generator PUBLIC ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(spire_test_generator PUBLIC spire_compiler fmt::fmt)
  spire_set_warnings(spire_test_generator)
endif()
