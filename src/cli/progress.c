/*
 * progress.c - terminal progress bar (see progress.h).
 */
#include "config.h"

#include "cli/progress.h"

#include <time.h>
#include <unistd.h>

double sph_wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void sph_progress_init(sph_progress *pg, FILE *out, double t_end, int quiet) {
  pg->out = out;
  pg->enabled = !quiet && isatty(fileno(out));
  pg->t_end = t_end;
  pg->wall0 = sph_wall_seconds();
  pg->last_draw = -1.0;
  pg->drawn = 0;
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

void sph_progress_update(sph_progress *pg, double t, long step) {
  if (!pg->enabled) return;
  const double now = sph_wall_seconds();
  if (pg->last_draw >= 0 && now - pg->last_draw < 0.2) return;
  pg->last_draw = now;
  const double el = now - pg->wall0;
  double frac = pg->t_end > 0 ? t / pg->t_end : 1.0;
  if (frac > 1) frac = 1;
  const int width = 30, fill = (int)(frac * width);
  char bar[64];
  for (int i = 0; i < width; i++)
    bar[i] = i < fill ? '#' : '.';
  bar[width] = 0;
  char eta[32];
  fmt_duration(eta, sizeof eta, frac > 0 ? el * (1 - frac) / frac : -1);
  fprintf(pg->out, "\r[%s] %5.1f%%  t = %.4f / %.4f s  step %ld  %.0f steps/s  ETA %s   ", bar,
          100 * frac, t, pg->t_end, step, el > 0 ? (double)step / el : 0.0, eta);
  fflush(pg->out);
  pg->drawn = 1;
}

void sph_progress_done(sph_progress *pg) {
  if (pg->enabled && pg->drawn) {
    fprintf(pg->out, "\r%*s\r", 100, "");
    fflush(pg->out);
  }
  pg->drawn = 0;
}
