/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * progress.c - terminal progress bar (see progress.h).
 */
#include "config.h"

#include "cli/progress.h"

#include <math.h>
#include <time.h>
#include <unistd.h>

double sph_wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void sph_progress_init(sph_progress *pg, FILE *out, double t_end, const char *measure, int quiet,
                       double log_every) {
  pg->out = out;
  const int tty = isatty(fileno(out));
  pg->enabled = !quiet && tty;
  pg->log_every = !quiet && !tty && log_every > 0.0 ? log_every : 0.0;
  pg->next_log = pg->log_every;
  pg->t_end = t_end;
  pg->wall0 = sph_wall_seconds();
  pg->last_draw = -1.0;
  pg->drawn = 0;
  pg->started = 0;
  pg->t0 = pg->m0 = 0.0;
  pg->step0 = 0;
  pg->measure = measure;
}

static double clamp01(double f) { return f < 0.0 ? 0.0 : f > 1.0 ? 1.0 : f; }

void sph_progress_state(const sph_progress *pg, double t, long step, double now, double stop,
                        double elapsed, double *by_time, double *by_stop, double *left) {
  (void)step;
  const double span = pg->t_end - pg->t0;
  *by_time = span > 0.0 ? clamp01((t - pg->t0) / span) : 1.0;
  *by_stop = -1.0;
  if (pg->measure && stop != pg->m0) *by_stop = clamp01((now - pg->m0) / (stop - pg->m0));
  /* the sooner of the two estimates, each extrapolating its own pace */
  *left = -1.0;
  const double f[2] = {*by_time, *by_stop};
  for (int k = 0; k < 2; k++)
    if (f[k] > 0.0) {
      const double est = elapsed * (1.0 - f[k]) / f[k];
      if (*left < 0.0 || est < *left) *left = est;
    }
}

static void fmt_duration(char *buf, size_t len, double s) {
  if (s < 0 || s > 1e7)
    snprintf(buf, len, "--");
  else if (s < 60)
    snprintf(buf, len, "%.0fs", s);
  else if (s < 3600)
    snprintf(buf, len, "%dm%02ds", (int)(s / 60), (int)s % 60);
  else
    snprintf(buf, len, "%dh%02dm", (int)(s / 3600), ((int)s % 3600) / 60);
}

/* The line written every log_every seconds into buf: "progress: t = ..." */
static void progress_line(const sph_progress *pg, double t, long step, double now, double stop,
                          double elapsed, char *buf, size_t len) {
  double ft, fs, left;
  sph_progress_state(pg, t, step, now, stop, elapsed, &ft, &fs, &left);
  char el[32], eta[32], cond[96] = "";
  fmt_duration(el, sizeof el, elapsed);
  fmt_duration(eta, sizeof eta, left);
  if (fs >= 0.0)
    snprintf(cond, sizeof cond, ", %s %.4g / %.4g m (%.0f%%)", pg->measure, now, stop, 100 * fs);
  snprintf(buf, len,
           "progress: t = %.4f / %.4f s (%.1f%%)%s, step %ld, %.0f steps/s, %s elapsed, ETA %s", t,
           pg->t_end, 100 * ft, cond, step,
           elapsed > 0 ? (double)(step - pg->step0) / elapsed : 0.0, el, eta);
}

void sph_progress_update(sph_progress *pg, double t, long step, double now, double stop) {
  if (!pg->started) {
    pg->started = 1;
    pg->t0 = t;
    pg->step0 = step;
    pg->m0 = now;
  }
  if (pg->log_every > 0.0) { /* a log: a line at each multiple of log_every */
    const double el = sph_wall_seconds() - pg->wall0;
    if (el < pg->next_log) return;
    pg->next_log = (floor(el / pg->log_every) + 1.0) * pg->log_every; /* the next multiple */
    char line[256];
    progress_line(pg, t, step, now, stop, el, line, sizeof line);
    fprintf(pg->out, "%s\n", line);
    fflush(pg->out);
    return;
  }
  if (!pg->enabled) return;
  const double wall = sph_wall_seconds();
  if (pg->last_draw >= 0 && wall - pg->last_draw < 0.2) return;
  pg->last_draw = wall;
  const double el = wall - pg->wall0;
  double ft, fs, left;
  sph_progress_state(pg, t, step, now, stop, el, &ft, &fs, &left);
  const double frac = fs > ft ? fs : ft;
  const int width = 30, fill = (int)(frac * width);
  char bar[64];
  for (int i = 0; i < width; i++)
    bar[i] = i < fill ? '#' : '.';
  bar[width] = 0;
  char eta[32], cond[96] = "";
  fmt_duration(eta, sizeof eta, left);
  if (fs >= 0.0)
    snprintf(cond, sizeof cond, "  %s %.4g / %.4g m (%.0f%%)", pg->measure, now, stop, 100 * fs);
  fprintf(pg->out, "\r[%s] %5.1f%%  t = %.4f / %.4f s%s  step %ld  %.0f steps/s  ETA %s   ", bar,
          100 * frac, t, pg->t_end, cond, step, el > 0 ? (double)(step - pg->step0) / el : 0.0,
          eta);
  fflush(pg->out);
  pg->drawn = 1;
}

void sph_progress_done(sph_progress *pg) {
  if (pg->enabled && pg->drawn) {
    fprintf(pg->out, "\r%*s\r", 140, "");
    fflush(pg->out);
  }
  pg->drawn = 0;
}
