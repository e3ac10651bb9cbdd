# Run by CMake (-P) after a test program is built in the sanitizer build: one ctest test per
# GoogleTest suite (`Suite.*`) instead of one per test (gtest_discover_tests). Every test still
# runs; what is saved is a process start per test, which under ASan + UBSan costs far more than
# in the release build (the shadow memory, the leak check at exit). docs/building.md, "Checks".
#
#   cmake -DTEST_EXECUTABLE=... -DTEST_FILE=... -DTEST_LABEL=... -DTEST_ENVIRONMENT=... -P add_suite_tests.cmake
cmake_minimum_required(VERSION 3.20)
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
                RESULT_VARIABLE status OUTPUT_VARIABLE listing ERROR_VARIABLE errors TIMEOUT 60)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${status}):\n${errors}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(script "")
foreach(line IN LISTS lines)
  # A suite line starts in the first column and ends its name with '.' (a typed or parameterized
  # suite adds "  # TypeParam = ..." after it); test lines are indented.
  if(line MATCHES "^([^ #][^ ]*)\\.( .*)?$")
    set(suite "${CMAKE_MATCH_1}")
    string(APPEND script
           "add_test([==[${suite}.*]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${suite}.*]==])\n"
           "set_tests_properties([==[${suite}.*]==] PROPERTIES LABELS [==[${TEST_LABEL}]==] "
           "ENVIRONMENT [==[${TEST_ENVIRONMENT}]==])\n")
  endif()
endforeach()
file(WRITE "${TEST_FILE}" "${script}")
