# Writes CTEST_FILE, the CTest tests of one GoogleTest program, one per test file: each runs the
# file's tests but the slow ones (TEST(Suite, Slow...), which tests/CMakeLists.txt adds one by one)
# in one process, named after the file (e.g. stability/contact_test). Run after the program is
# built (cmake -P), as gtest_discover_tests lists its tests. Arguments (-D):
#   TEST_EXECUTABLE  the program
#   SOURCE_DIR       the folder the names are relative to (tests/)
#   WORKING_DIR      the tests' working folder
#   CTEST_FILE       the file to write
#   TIMEOUT          seconds the listing may take
#   TEST_TMP         SHADOW_TEST_TMP of the tests' environment
#   LSAN             (optional) an ENVIRONMENT_MODIFICATION entry for LeakSanitizer
foreach(var TEST_EXECUTABLE SOURCE_DIR WORKING_DIR CTEST_FILE TIMEOUT TEST_TMP)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "file_tests.cmake: ${var} is not set")
  endif()
endforeach()

set(listing "${CTEST_FILE}.json")
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests "--gtest_filter=-*.Slow*"
                        "--gtest_output=json:${listing}"
                WORKING_DIRECTORY "${WORKING_DIR}" TIMEOUT ${TIMEOUT} OUTPUT_VARIABLE output RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "file_tests.cmake: listing the tests of ${TEST_EXECUTABLE} failed (${result}):\n${output}")
endif()
file(READ "${listing}" json)
file(REMOVE "${listing}")

# The tests of each file, in the program's order: "Suite.Name" joined by ':' (a GoogleTest filter).
set(files)
string(JSON suites LENGTH "${json}" testsuites)
if(suites GREATER 0)
  math(EXPR last_suite "${suites} - 1")
  foreach(s RANGE ${last_suite})
    string(JSON suite GET "${json}" testsuites ${s} name)
    string(JSON cases LENGTH "${json}" testsuites ${s} testsuite)
    if(cases EQUAL 0)
      continue()
    endif()
    math(EXPR last_case "${cases} - 1")
    foreach(c RANGE ${last_case})
      string(JSON name GET "${json}" testsuites ${s} testsuite ${c} name)
      string(JSON path GET "${json}" testsuites ${s} testsuite ${c} file)
      file(RELATIVE_PATH path "${SOURCE_DIR}" "${path}")
      string(REGEX REPLACE "\\.cpp$" "" path "${path}")
      string(MAKE_C_IDENTIFIER "${path}" key)
      if(NOT DEFINED filter_${key})
        list(APPEND files "${path}")
        set(filter_${key} "${suite}.${name}")
      else()
        string(APPEND filter_${key} ":${suite}.${name}")
      endif()
    endforeach()
  endforeach()
endif()

set(properties "WORKING_DIRECTORY [==[${WORKING_DIR}]==] ENVIRONMENT [==[SHADOW_TEST_TMP=${TEST_TMP}]==]")
if(LSAN)
  string(APPEND properties " ENVIRONMENT_MODIFICATION [==[${LSAN}]==]")
endif()
set(script "")
foreach(path IN LISTS files)
  string(MAKE_C_IDENTIFIER "${path}" key)
  string(APPEND script "add_test([==[${path}]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${filter_${key}}]==])\n"
         "set_tests_properties([==[${path}]==] PROPERTIES ${properties})\n")
endforeach()
file(WRITE "${CTEST_FILE}" "${script}")
