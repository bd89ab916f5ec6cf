# Included by ctest (TEST_INCLUDE_FILES; add_gtest_suites in tests/CMakeLists.txt): one ctest test
# per GoogleTest suite of EXE, `EXE --gtest_filter=SUITE.*`, named PREFIX + SUITE. The suites are
# listed when ctest runs, so a test added to the sources needs no reconfiguration.
if(NOT EXISTS "${EXE}")
  add_test("${PREFIX}not_built" "${EXE}")
  return()
endif()
# ENVIRONMENT: the sanitizers' options for a sanitized EXE (without them LeakSanitizer fails the listing).
execute_process(COMMAND "${CMAKE_EXE}" -E env ${ENVIRONMENT} "${EXE}" --gtest_list_tests WORKING_DIRECTORY "${WORKDIR}" TIMEOUT 60
                OUTPUT_VARIABLE listing ERROR_VARIABLE listing_error RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE} --gtest_list_tests failed (${rc}): ${listing_error}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
foreach(line IN LISTS lines)
  # Suite lines start in column 1 and end with '.', test lines are indented.
  if(line MATCHES "^([^ #][^ ]*)\\.")
    set(suite "${CMAKE_MATCH_1}")
    # EXCLUDED_SUITES: run by another binary (unit_tests_slow, tests/CMakeLists.txt).
    list(FIND EXCLUDED_SUITES "${suite}" excluded)
    if(NOT excluded EQUAL -1)
      continue()
    endif()
    add_test("${PREFIX}${suite}" "${EXE}" "--gtest_filter=${suite}.*")
    set_tests_properties("${PREFIX}${suite}" PROPERTIES WORKING_DIRECTORY "${WORKDIR}" TIMEOUT "${TIMEOUT}")
    if(ENVIRONMENT)
      set_tests_properties("${PREFIX}${suite}" PROPERTIES ENVIRONMENT "${ENVIRONMENT}")
    endif()
  endif()
endforeach()
