/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * render_testutil.h - what the renderer's tests (test_render, test_render_3d)
 * share: reading a PNG back, and comparing an image with its golden copy
 * in golden/render/.
 *
 * Golden images are compared pixel by pixel with a tolerance, because
 * other Mesa drivers than llvmpipe rasterise edges slightly differently: a
 * pixel differs if a channel is off by more than RGOLDEN_CHANNEL_TOL; at
 * most RGOLDEN_PIXEL_FRACTION of the pixels may differ, and the mean
 * absolute channel difference must stay below RGOLDEN_MEAN_TOL. With
 * llvmpipe the images match exactly. `make golden-render` runs the tests
 * with SPH_RENDER_REGEN=1, which copies the images over the golden ones.
 */
#ifndef SPH_TESTS_RENDER_TESTUTIL_H
#define SPH_TESTS_RENDER_TESTUTIL_H

#include <stdint.h>

#define RGOLDEN_CHANNEL_TOL 8
#define RGOLDEN_PIXEL_FRACTION 0.002
#define RGOLDEN_MEAN_TOL 0.5

/* Runs sph-render (the build's) in directory dir with args (a shell
 * fragment), the environment assignments env ("" for none) before it, its
 * stderr into dir/err.txt; the shell's status. */
int rtest_render(const char *dir, const char *env, const char *args);
/* That stderr (dir/err.txt), in a static buffer; "" if none. */
const char *rtest_last_err(const char *dir);
/* Whether files a and b hold the same bytes (both readable). */
int rtest_same_bytes(const char *a, const char *b);
/* Whether SPH_RENDER_REGEN=1 (regenerate the golden images). */
int rtest_regen(void);
/* A PNG as 8-bit RGB (malloc'd), its size in w and h; NULL if unreadable. */
uint8_t *rtest_read_png(const char *path, int *w, int *h);
/* Compares image with golden/render/<name> within the tolerances above
 * (CUnit assertions), or, when regenerating and may_regen is set, copies
 * it there. */
void rtest_check_golden(const char *image, const char *name, int may_regen);

#endif
