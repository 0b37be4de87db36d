/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * testmain.c - the CUnit runner every test program ends with (testutil.h).
 * Apart from the other helpers because it needs no part of the library: a
 * test of the 3-D build links it without the 2-D library.
 */
#include "config.h"

#include "testutil.h"

#include <CUnit/Basic.h>
#include <stdio.h>

int sph_test_main(const char *suite, CU_TestInfo *tests) {
  CU_SuiteInfo suites[] = {{suite, NULL, NULL, NULL, NULL, tests}, CU_SUITE_INFO_NULL};
  if (CU_initialize_registry() != CUE_SUCCESS) return 2;
  if (CU_register_suites(suites) != CUE_SUCCESS) {
    fprintf(stderr, "%s: cannot register suite: %s\n", suite, CU_get_error_msg());
    CU_cleanup_registry();
    return 2;
  }
  CU_basic_set_mode(CU_BRM_VERBOSE);
  CU_basic_run_tests();
  unsigned failed = CU_get_number_of_failures();
  unsigned tests_failed = CU_get_number_of_tests_failed();
  unsigned ran = CU_get_number_of_tests_run();
  CU_cleanup_registry();
  printf("%s: %u passed, %u failed\n", suite, ran - tests_failed, tests_failed);
  if (ran == 0) return 1; /* a suite that runs nothing is a failure */
  return failed ? 1 : 0;
}
