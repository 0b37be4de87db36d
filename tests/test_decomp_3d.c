/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_decomp_3d.c - test_decomp.c as the 3-D build compiles it (-DSPH_DIM=3,
 * linked with src/libsph3.la): the Hilbert curve in three dimensions and
 * ranks emulated on 3-D cases.
 */
#include "test_decomp.c"
