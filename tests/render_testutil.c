/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * render_testutil.c - PNG read-back and golden images for the renderer's
 * tests (see render_testutil.h).
 */
#include "config.h"

#include "render_testutil.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"

int rtest_render(const char *dir, const char *env, const char *args) {
  char cmd[16384];
  snprintf(cmd, sizeof cmd, "cd '%s' && %s '%s' %s 2> '%s/err.txt'", dir, env,
           sph_test_build("render/sph-render"), args, dir);
  return sph_test_system(cmd);
}

const char *rtest_last_err(const char *dir) {
  static char buf[8192];
  char path[4200];
  snprintf(path, sizeof path, "%s/err.txt", dir);
  buf[0] = '\0';
  FILE *fp = fopen(path, "r");
  if (fp) {
    size_t n = fread(buf, 1, sizeof buf - 1, fp);
    buf[n] = '\0';
    fclose(fp);
  }
  return buf;
}

int rtest_same_bytes(const char *a, const char *b) {
  size_t na, nb;
  char *x = sph_test_read_file(a, &na), *y = sph_test_read_file(b, &nb);
  const int same = x && y && na == nb && memcmp(x, y, na) == 0;
  free(x);
  free(y);
  return same;
}

int rtest_regen(void) {
  const char *r = getenv("SPH_RENDER_REGEN");
  return r && strcmp(r, "1") == 0;
}

uint8_t *rtest_read_png(const char *path, int *w, int *h) {
  png_image img;
  memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path)) return NULL;
  img.format = PNG_FORMAT_RGB;
  uint8_t *buf = malloc(PNG_IMAGE_SIZE(img));
  if (!buf || !png_image_finish_read(&img, NULL, buf, 0, NULL)) {
    free(buf);
    png_image_free(&img);
    return NULL;
  }
  *w = (int)img.width;
  *h = (int)img.height;
  return buf;
}

void rtest_check_golden(const char *image, const char *name, int may_regen) {
  char golden[4096];
  snprintf(golden, sizeof golden, "%s", sph_test_src("golden/render/"));
  strncat(golden, name, sizeof golden - strlen(golden) - 1);
  if (rtest_regen() && may_regen) {
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "cp '%s' '%s'", image, golden);
    CU_ASSERT_EQUAL_FATAL(sph_test_system(cmd), 0);
    printf("\n  regenerated %s\n", golden);
    return;
  }
  int w, h, gw, gh;
  uint8_t *a = rtest_read_png(image, &w, &h);
  uint8_t *b = rtest_read_png(golden, &gw, &gh);
  CU_ASSERT_PTR_NOT_NULL_FATAL(a);
  if (!b) {
    printf("\n  missing golden image %s (make golden-render)\n", golden);
    free(a);
    CU_FAIL_FATAL("golden image missing");
  }
  CU_ASSERT_EQUAL(w, gw);
  CU_ASSERT_EQUAL(h, gh);
  if (w == gw && h == gh) {
    size_t n = (size_t)w * h, differ = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
      int worst = 0;
      for (int c = 0; c < 3; c++) {
        int d = abs((int)a[3 * i + c] - (int)b[3 * i + c]);
        sum += d;
        if (d > worst) worst = d;
      }
      if (worst > RGOLDEN_CHANNEL_TOL) differ++;
    }
    double mean = sum / (3.0 * n);
    if (differ > RGOLDEN_PIXEL_FRACTION * n || mean > RGOLDEN_MEAN_TOL)
      printf("\n  %s vs %s: %zu of %zu pixels differ, mean difference %.3f\n", image, golden,
             differ, n, mean);
    CU_ASSERT(differ <= RGOLDEN_PIXEL_FRACTION * n);
    CU_ASSERT(mean <= RGOLDEN_MEAN_TOL);
  }
  free(a);
  free(b);
}
