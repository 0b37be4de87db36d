/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * gl_supersample.c - sub-pixels that fit, and the averaged read-back (see
 * gl_supersample.h).
 */
#include "config.h"

#include "gl_supersample.h"

#include <stdlib.h>

int rgl_fit_samples(const rgl *gl, int w, int h, int samples, double bytes_per_sample,
                    sph_error *err) {
  GLint max_rb = 0, max_vp[2] = {0, 0};
  gl->GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
  gl->GetIntegerv(GL_MAX_VIEWPORT_DIMS, max_vp);
  const int lim_x = max_rb < max_vp[0] ? max_rb : max_vp[0];
  const int lim_y = max_rb < max_vp[1] ? max_rb : max_vp[1];
  if (w > lim_x || h > lim_y)
    return sph_error_set(err, "image size %dx%d exceeds the driver's limit of %dx%d", w, h, lim_x,
                         lim_y);
  while (samples > 1 && ((double)w * samples > lim_x || (double)h * samples > lim_y ||
                         bytes_per_sample * w * h * samples * samples > RGL_FRAMEBUFFER_BYTES_MAX))
    samples--;
  return samples;
}

int rgl_read_averaged(const rgl *gl, int w, int h, int samples, int channels, uint8_t *out,
                      const char *who, sph_error *err) {
  const int dw = w * samples, dh = h * samples;
  const size_t row = (size_t)dw * 4;
  uint8_t *rgba = malloc(row * (size_t)dh);
  if (!rgba) return sph_error_set(err, "%s: out of memory reading %dx%d pixels", who, dw, dh);
  gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl->ReadPixels(0, 0, dw, dh, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  if (gl->GetError() != GL_NO_ERROR) {
    free(rgba);
    return sph_error_set(err, "%s: glReadPixels failed", who);
  }
  const unsigned n = (unsigned)(samples * samples);
  for (int y = 0; y < h; y++) {
    uint8_t *dst = out + (size_t)y * w * channels;
    for (int x = 0; x < w; x++) {
      unsigned sum[3] = {0, 0, 0};
      for (int j = 0; j < samples; j++) {
        /* framebuffer row of sub-pixel row j of image row y (bottom-up) */
        const uint8_t *src =
            rgba + (size_t)(dh - 1 - (y * samples + j)) * row + (size_t)x * samples * 4;
        for (int i = 0; i < samples; i++)
          for (int k = 0; k < 3; k++)
            sum[k] += src[4 * i + k];
      }
      for (int k = 0; k < 3; k++)
        dst[channels * x + k] = (uint8_t)((sum[k] + n / 2) / n);
      if (channels == 4) dst[4 * x + 3] = 255;
    }
  }
  free(rgba);
  return 0;
}
