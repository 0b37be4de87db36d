/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * sequence.c - plans and renders the images of the snapshot modes.
 *
 * Planning happens once, in the main process, before any image is drawn:
 * the inputs are expanded, matched by time if needed, and turned into tasks
 * (one output PNG each, holding one or more panels); the colour range is
 * taken over every snapshot of every task, unless --range fixes it, so the
 * frames of a run share one scale and a missing field or unreadable file
 * stops everything before the first PNG; the layout is computed from the
 * view and the range. Then the tasks run on worker processes (jobs.c), each
 * of which loads its snapshots again, draws and writes its PNG atomically.
 * Everything a task draws is fixed by the plan, so the same inputs give the
 * same bytes for any number of workers.
 */
#include "config.h"

#include "sequence.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "colormap.h"
#include "figure.h"
#include "font.h"
#include "gl_context.h"
#include "inputs.h"
#include "io/csv.h"
#include "io/snapshot.h"
#include "jobs.h"
#include "label.h"
#include "layout.h"
#include "marks.h"
#include "obstacles.h"
#include "png_out.h"
#include "scene3d.h"
#include "slice.h"
#include "snapdata.h"
#include "spheres.h"
#include "surface.h"

typedef struct rtask {
  char *output;
  int n;
  const char *path[RLAYOUT_MAX_PANELS];
  char label[RLAYOUT_MAX_PANELS][96]; /* run name or panel letter prefix */
} rtask;

typedef struct plan {
  const roptions *o;
  rtask *task;
  size_t n_task;
  rcolormap cmap;
  rlayout layout;
  rfigure_style style;
  roverlay overlay[16];
  char bar_label[96];
  const char *outdir; /* made only once the plan is complete; NULL: one file */
  int dim3;           /* the inputs are 3-D snapshots: drawn as spheres by cam */
  int sliced;         /* 3-D snapshots cut by o->slice: drawn as 2-D ones */
  rcamera cam;
  rmesh boxes;    /* 3-D: the obstacles' faces (obstacles.h) */
  double tank[6]; /* 3-D: the tank's inner faces, NaN if not listed */
  uint8_t *boxes_rgba;
} plan;

typedef struct worker {
  rgl_context *gl;
  rcanvas *canvas;
  uint8_t *rgb;
} worker;

static void panel_letter(int k, char *buf, size_t size) {
  if (k < 26)
    snprintf(buf, size, "%c)", 'a' + k);
  else
    snprintf(buf, size, "%c%d)", 'a' + k % 26, k / 26);
}

static rtask *add_task(plan *p, sph_error *err) {
  rtask *t = realloc(p->task, (p->n_task + 1) * sizeof *t);
  if (!t) {
    sph_error_set(err, "out of memory");
    return NULL;
  }
  p->task = t;
  memset(&t[p->n_task], 0, sizeof *t);
  return &t[p->n_task++];
}

/* dir/prefix_NUMBER.png, NUMBER from the snapshot's name (or its stem). */
static char *output_in_dir(const char *dir, const char *prefix, const char *snap) {
  char num[256], stem[256];
  rinputs_number(snap, num, sizeof num);
  rinputs_stem(snap, stem, sizeof stem);
  size_t len = strlen(dir) + strlen(prefix) + strlen(stem) + 16;
  char *out = malloc(len);
  if (!out) return NULL;
  if (num[0])
    snprintf(out, len, "%s/%s_%s.png", dir, prefix, num);
  else
    snprintf(out, len, "%s/%s.png", dir, stem);
  return out;
}

static int check_unique_outputs(const plan *p, sph_error *err) {
  for (size_t i = 0; i < p->n_task; i++)
    for (size_t j = i + 1; j < p->n_task; j++)
      if (strcmp(p->task[i].output, p->task[j].output) == 0)
        return sph_error_set(err, "%s and %s would both be written to %s", p->task[i].path[0],
                             p->task[j].path[0], p->task[i].output);
  return 0;
}

/* Whether -o names one image file (PNG, SVG or PDF) rather than a directory. */
static int one_file(const char *path) { return rinputs_is_png(path) || rcanvas_vector_kind(path); }

static int plan_frames(plan *p, rinputs *in, sph_error *err) {
  const roptions *o = p->o;
  int single = one_file(o->output);
  /* --times: the nearest snapshot to each time, each at most once */
  size_t n = o->n_times > 0 ? (size_t)o->n_times : in->n;
  if (o->n_times > 0 && rinputs_times(in, err) != 0) return -1;
  if (single && n != 1)
    return sph_error_set(err, "-o %s names one image but there are %zu snapshots: give a directory",
                         o->output, n);
  p->outdir = single ? NULL : o->output;
  for (size_t i = 0; i < n; i++) {
    const char *path = in->v[o->n_times > 0 ? rinputs_nearest(in, o->times[i]) : i].path;
    int dup = 0;
    for (size_t j = 0; j < p->n_task; j++)
      dup |= p->task[j].path[0] == path;
    if (dup) continue;
    rtask *t = add_task(p, err);
    if (!t) return -1;
    t->n = 1;
    t->path[0] = path;
    t->output = single ? strdup(o->output) : output_in_dir(o->output, "frame", path);
    if (!t->output) return sph_error_set(err, "out of memory");
  }
  return check_unique_outputs(p, err);
}

static int plan_panels(plan *p, rinputs *in, sph_error *err) {
  const roptions *o = p->o;
  if (!one_file(o->output))
    return sph_error_set(err,
                         "--panels writes one figure: -o must name a .png, .svg or .pdf file, "
                         "not '%s'",
                         o->output);
  int max = o->cols * o->rows;
  rtask *t = add_task(p, err);
  if (!t) return -1;
  t->output = strdup(o->output);
  if (!t->output) return sph_error_set(err, "out of memory");
  if (o->n_times > 0) {
    if (o->n_times > max)
      return sph_error_set(err, "%d times for %dx%d panels", o->n_times, o->cols, o->rows);
    if (rinputs_times(in, err) != 0) return -1;
    for (int k = 0; k < o->n_times; k++)
      t->path[t->n++] = in->v[rinputs_nearest(in, o->times[k])].path;
  } else {
    if ((int)in->n > max)
      return sph_error_set(err, "%zu snapshots do not fit %dx%d panels (pick some with --times)",
                           in->n, o->cols, o->rows);
    for (size_t i = 0; i < in->n; i++)
      t->path[t->n++] = in->v[i].path;
  }
  for (int k = 0; k < t->n; k++)
    panel_letter(k, t->label[k], sizeof t->label[k]);
  return 0;
}

static int plan_compare(plan *p, rinputs *runs, int n_runs, sph_error *err) {
  const roptions *o = p->o;
  for (int r = 0; r < n_runs; r++)
    if (rinputs_times(&runs[r], err) != 0) return -1;
  /* the times to show: the requested ones, or every snapshot of the first run */
  rinputs *first = &runs[0];
  double tol = o->match_tol;
  if (isnan(tol)) {
    double sp = rinputs_min_spacing(first);
    tol = isfinite(sp) ? 0.5 * sp : INFINITY;
  }
  size_t n_times = o->n_times > 0 ? (size_t)o->n_times : first->n;
  int single = one_file(o->output);
  p->outdir = single ? NULL : o->output;
  for (size_t i = 0; i < n_times; i++) {
    size_t i0 = o->n_times > 0 ? rinputs_nearest(first, o->times[i]) : i;
    double t0 = o->n_times > 0 ? o->times[i] : first->v[i0].time;
    const char *paths[RLAYOUT_MAX_PANELS];
    int ok = 1;
    for (int r = 0; r < n_runs; r++) {
      size_t j = rinputs_nearest(&runs[r], t0);
      if (o->n_times == 0 && fabs(runs[r].v[j].time - t0) > tol) ok = 0;
      paths[r] = runs[r].v[j].path;
    }
    if (!ok) {
      if (o->verbose)
        fprintf(stderr, "note: t = %g s of %s has no match in every run; skipped\n", t0,
                first->v[i0].path);
      continue;
    }
    rtask *t = add_task(p, err);
    if (!t) return -1;
    t->n = n_runs;
    for (int r = 0; r < n_runs; r++) {
      char letter[16], name[64];
      panel_letter(r, letter, sizeof letter);
      if (r < o->n_names)
        snprintf(name, sizeof name, "%s", o->names[r]);
      else
        rinputs_stem(o->inputs[r], name, sizeof name);
      t->path[r] = paths[r];
      snprintf(t->label[r], sizeof t->label[r], "%s %s", letter, name);
    }
    t->output = single ? strdup(o->output) : output_in_dir(o->output, "compare", first->v[i0].path);
    if (!t->output) return sph_error_set(err, "out of memory");
  }
  if (p->n_task == 0)
    return sph_error_set(err, "no time of %s matches a snapshot of every run (within %g s)",
                         o->inputs[0], tol);
  if (single && p->n_task != 1)
    return sph_error_set(err,
                         "-o %s names one PNG but %zu times match: give a directory or "
                         "one --times value",
                         o->output, p->n_task);
  return check_unique_outputs(p, err);
}

/* The colour range over every snapshot the plan draws, and the view. */
static int plan_range_and_view(plan *p, double view[4], sph_error *err) {
  const roptions *o = p->o;
  double lo = 0.0, hi = 0.0;
  size_t count = 0;
  int need_range = !o->have_range;
  view[0] = view[1] = view[2] = view[3] = NAN;
  for (size_t i = 0; i < p->n_task; i++) {
    for (int k = 0; k < p->task[i].n; k++) {
      const char *path = p->task[i].path[k];
      if (!need_range && !p->sliced) {
        double t;
        if (isnan(view[0]) && !o->have_view && rsnap_peek(path, &t, view, err) != 0) return -1;
        continue;
      }
      if (!need_range && (!isnan(view[0]) || o->have_view)) continue;
      rsnap s;
      if (rsnap_load_phases(path, o->field, o->air, &s, err) != 0) return -1;
      if (p->sliced && rslice_apply(&o->slice, &s, err) != 0) {
        rsnap_free(&s);
        return -1;
      }
      if (isnan(view[0])) memcpy(view, s.view, 4 * sizeof *view);
      double a = 0.0, b = 0.0;
      if (rsnap_fluid_range(&s, &a, &b) > 0) {
        if (count == 0 || a < lo) lo = a;
        if (count == 0 || b > hi) hi = b;
        count++;
      }
      rsnap_free(&s);
    }
  }
  if (p->dim3) { /* no world window: the plot box's aspect, 16:9 for frames, 4:3 for panels */
    if (o->have_view)
      return sph_error_set(err, "--view X0:X1:Y0:Y1 is for 2-D snapshots; %s is 3-D (views: %s)",
                           p->task[0].path[0], rcamera_names());
    const double a = o->mode == RMODE_FRAMES ? 16.0 / 9.0 : 4.0 / 3.0;
    view[0] = view[2] = 0.0;
    view[1] = a;
    view[3] = 1.0;
  }
  if (o->have_view) memcpy(view, o->view, 4 * sizeof *view);
  if (isnan(view[0]))
    return sph_error_set(err, "%s: no view window (attribute 'view'); give --view x0:x1:y0:y1",
                         p->task[0].path[0]);
  if (o->have_range) {
    lo = o->range[0];
    hi = o->range[1];
  } else {
    if (count == 0) lo = hi = 0.0;
    /* a non-negative range that nearly reaches zero starts at zero (speed) */
    if (lo > 0.0 && lo < 0.1 * hi) lo = 0.0;
    if (p->cmap.diverging) {
      double m = fmax(fabs(lo), fabs(hi));
      lo = -m;
      hi = m;
    }
    if (!(hi > lo)) {
      double pad = fabs(lo) > 0.0 ? 0.5 * fabs(lo) : 0.5;
      lo -= pad;
      hi += pad;
    }
  }
  p->style.lo = lo;
  p->style.hi = hi;
  return 0;
}

/* The obstacles' boxes of the first snapshot (the case's; they do not
 * move), as a light grey mesh drawn in every 3-D view, and the tank's
 * inner faces, whose edges are drawn: from the snapshot's /geometry, or
 * in a snapshot written before it existed from its parameter listing. */
static int plan_obstacles(plan *p, sph_error *err) {
  sph_snapshot *s = NULL;
  if (sph_snapshot_open_any(p->task[0].path[0], &s, err) != 0) return -1;
  double box[ROBSTACLES_MAX][6];
  int n = 0;
  sph_snapshot_geometry geo;
  const int old = sph_snapshot_read_geometry(s, &geo, err);
  if (old < 0) {
    sph_snapshot_close(s);
    return -1;
  }
  if (old) {
    const char *parameters = sph_snapshot_text(s, "parameters");
    n = robstacles_parse(parameters, box, ROBSTACLES_MAX);
    if (robstacles_tank(parameters, p->tank) != 0) p->tank[0] = NAN;
  } else {
    p->tank[0] = NAN;
    if (geo.dim == 3) { /* boxes in three axes only */
      for (size_t k = 0; k < geo.n_obstacles && n < ROBSTACLES_MAX; k++, n++)
        memcpy(box[n], geo.obstacles[k], sizeof box[n]);
      if (geo.has_tank) memcpy(p->tank, geo.tank, sizeof geo.tank);
    }
    sph_snapshot_geometry_free(&geo);
  }
  sph_snapshot_close(s);
  if (robstacles_mesh((const double(*)[6])box, n, &p->boxes, err) != 0) return -1;
  p->boxes_rgba = malloc(4 * (p->boxes.nv ? p->boxes.nv : 1));
  if (!p->boxes_rgba) return sph_error_set(err, "out of memory");
  for (size_t i = 0; i < 4 * p->boxes.nv; i++)
    p->boxes_rgba[i] = i % 4 == 3 ? 255 : 200;
  return 0;
}

/* The camera of a 3-D plan, the same for every image: the named view (iso
 * by default) or the given direction, framing the first snapshot's tank
 * (its attribute view; else its particles' box) in the first panel's plot
 * box, unless --look-at and --distance say where it is. */
static int plan_camera(plan *p, sph_error *err) {
  const roptions *o = p->o;
  rcamera *c = &p->cam;
  memset(c, 0, sizeof *c);
  if (rcamera_named(o->view3d ? o->view3d : "iso", &c->azimuth, &c->elevation) != 0)
    return sph_error_set(err, "--view: unknown view '%s' (%s)", o->view3d, rcamera_names());
  if (o->have_azimuth) c->azimuth = o->azimuth;
  if (o->have_elevation) c->elevation = o->elevation;
  c->fov = o->fov;
  c->ortho = o->ortho;
  rsnap s;
  if (rsnap_load_phases(p->task[0].path[0], NULL, o->air, &s, err) != 0) return -1;
  double lo[3], hi[3];
  for (int k = 0; k < 3; k++) {
    lo[k] = s.box[2 * k];
    hi[k] = s.box[2 * k + 1];
  }
  if (!(hi[0] > lo[0] && hi[1] > lo[1] && hi[2] > lo[2])) { /* the particles' box */
    for (int k = 0; k < 3; k++)
      lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t i = 0; i < s.n; i++) {
      const double q[3] = {s.x[i], s.y[i], s.z[i]};
      for (int k = 0; k < 3; k++)
        lo[k] = fmin(lo[k], q[k]), hi[k] = fmax(hi[k], q[k]);
    }
  }
  rsnap_free(&s);
  if (!(hi[0] >= lo[0])) return sph_error_set(err, "%s: no particles to frame", p->task[0].path[0]);
  const rrect *b = &p->layout.panel[0].plot;
  rcamera_frame_box(c, lo, hi, (b->x1 - b->x0) / (b->y1 - b->y0));
  if (plan_obstacles(p, err) != 0) return -1;
  if (o->have_look_at) memcpy(c->look_at, o->look_at, sizeof c->look_at);
  if (o->have_distance) c->distance = o->distance;
  return rcamera_check(c, err);
}

/* The colour of the surface drawn as water (--surface water). */
static const uint8_t water_rgb[3] = {70, 130, 190};

/* The free surface of s as a mesh and one colour per vertex (the field's,
 * or water's), for panel views with --surface. */
static int surface_of(const plan *p, const rsnap *s, rmesh *m, uint8_t **rgba, sph_error *err) {
  const int by_field = p->o->surface == RSURFACE_FIELD;
  double cell;
  if (rsurface_cell(s, p->o->surface_cell, &cell, err) != 0 ||
      rsurface_of(s, cell, by_field, m, err) != 0)
    return -1;
  *rgba = malloc(4 * (m->nv ? m->nv : 1));
  if (!*rgba) {
    rmesh_free(m);
    return sph_error_set(err, "%s: out of memory for %zu vertices", s->path, m->nv);
  }
  for (size_t i = 0; i < m->nv; i++) {
    uint8_t rgb[3] = {water_rgb[0], water_rgb[1], water_rgb[2]};
    if (by_field) rfigure_color(&p->style, m->val[i], rgb);
    uint8_t *q = *rgba + 4 * i;
    q[0] = rgb[0], q[1] = rgb[1], q[2] = rgb[2], q[3] = 255;
  }
  return 0;
}

/* Panel k's 3-D view of snapshot s: its fluid particles as spheres each of
 * its own size (the cube root of its volume m / rho, times --disc-scale;
 * --disc-size fixes one; grown if small on the image), coloured as discs are, or its free surface
 * as a mesh (--surface), and its walls as spheres of the discs' diameter with
 * --walls grey or field, drawn by the worker's context into a malloc'd
 * RGBA image of the plot box's size. */
static int draw_3d(const plan *p, worker *w, int k, const rsnap *s, rpanel *pa, sph_error *err) {
  if (s->dim != 3)
    return sph_error_set(err, "%s: a 2-D snapshot among 3-D ones: draw them apart", s->path);
  const rfigure_style *st = &p->style;
  double diameter;
  if (rfigure_disc_size(st, s, &diameter, err) != 0) return -1;
  const int walls = p->o->walls_given && st->walls != RWALLS_NONE;
  const int surface = p->o->surface != RSURFACE_NONE;
  const int own_size = s->vol && !(st->disc_size > 0.0); /* fluid: (m / rho)^(1/3) */
  rmesh mesh = {0};
  uint8_t *mesh_rgba = NULL;
  if (surface && surface_of(p, s, &mesh, &mesh_rgba, err) != 0) return -1;
  rsphere *sp = malloc((s->n ? s->n : 1) * sizeof *sp);
  const rrect *b = &p->layout.panel[k].plot;
  const int iw = (int)(b->x1 - b->x0), ih = (int)(b->y1 - b->y0);
  uint8_t *img = malloc((size_t)iw * (size_t)ih * 4);
  if (!sp || !img) {
    free(sp);
    free(img);
    rmesh_free(&mesh);
    free(mesh_rgba);
    return sph_error_set(err, "%s: out of memory for %zu spheres", s->path, s->n);
  }
  /* spheres under 4 pixels across at the camera's target grow as 2-D discs
   * do (figure.h), up to sqrt(2) below 2 pixels, so that a fine run's
   * particles cover their cells rather than leave the background between
   * them; --disc-scale or --disc-size turns this off */
  const double view_h =
      p->cam.ortho ? p->cam.height : 2.0 * p->cam.distance * tan(0.5 * p->cam.fov * M_PI / 180.0);
  const double grow = st->grow_small ? rfigure_growth(diameter / view_h * ih) : 1.0;
  size_t n = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->wall[i] ? !walls : surface) continue;
    rsphere *q = &sp[n++];
    q->c[0] = (float)s->x[i], q->c[1] = (float)s->y[i], q->c[2] = (float)s->z[i];
    q->r = (float)(0.5 * diameter * grow);
    if (own_size && !s->wall[i] && s->vol[i] > 0.0) /* its own volume's cube */
      q->r = (float)(0.5 * st->disc_scale * cbrt(s->vol[i]) * grow);
    uint8_t rgb[3] = {st->wall.r, st->wall.g, st->wall.b};
    if (!s->wall[i] || st->walls == RWALLS_FIELD) rfigure_color(st, s->val[i], rgb);
    q->rgba[0] = rgb[0], q->rgba[1] = rgb[1], q->rgba[2] = rgb[2], q->rgba[3] = 255;
  }
  rscene3d sc = {sp,
                 n,
                 {surface ? &mesh : NULL, p->boxes.nt ? &p->boxes : NULL},
                 {mesh_rgba, p->boxes_rgba},
                 NULL,
                 0,
                 0.0,
                 {st->fg.r, st->fg.g, st->fg.b, 90}};
  float edges[12][6]; /* the tank's twelve edges, faint */
  const double *bx = isfinite(p->tank[0]) ? p->tank : s->box;
  for (int e = 0; e < 12 && isfinite(bx[0]); e++) {
    const int axis = e / 4, o1 = (axis + 1) % 3, o2 = (axis + 2) % 3; /* along axis, at a corner */
    for (int end = 0; end < 2; end++) {
      float *q = edges[e] + 3 * end;
      q[o1] = (float)bx[2 * o1 + (e & 1)];
      q[o2] = (float)bx[2 * o2 + ((e >> 1) & 1)];
      q[axis] = (float)bx[2 * axis + end];
    }
    sc.n_segments++;
  }
  sc.segments = edges[0];
  sc.segment_width = rlayout_line_width(&p->layout);
  int rc = rscene3d_draw(&w->gl->gl, &p->cam, iw, ih, p->o->samples, &sc, st->bg, img, err);
  free(sp);
  rmesh_free(&mesh);
  free(mesh_rgba);
  if (rc) {
    free(img);
    return -1;
  }
  pa->image = img;
  pa->iw = iw;
  pa->ih = ih;
  return 0;
}

static int load_overlays(plan *p, sph_error *err) {
  const roptions *o = p->o;
  for (int i = 0; i < o->n_overlays; i++) {
    const roverlay_opt *ov = &o->overlay[i];
    roverlay *dst = &p->overlay[i];
    sph_csv t;
    if (sph_csv_read(ov->path, &t, err) != 0) return -1;
    int rc = 0;
    if (t.ncol < 2 && (!ov->xcol || !ov->ycol))
      rc = sph_error_set(err, "%s: an overlay needs two columns (x, y)", ov->path);
    dst->n = t.nrow;
    dst->x = malloc((t.nrow + 1) * sizeof *dst->x);
    dst->y = malloc((t.nrow + 1) * sizeof *dst->y);
    if (ov->tcol) dst->t = malloc((t.nrow + 1) * sizeof *dst->t);
    if (!rc && (!dst->x || !dst->y || (ov->tcol && !dst->t)))
      rc = sph_error_set(err, "out of memory");
    if (!rc) rc = sph_csv_eval(&t, ov->xcol ? ov->xcol : t.names[0], dst->x, err);
    if (!rc) rc = sph_csv_eval(&t, ov->ycol ? ov->ycol : t.names[1], dst->y, err);
    if (!rc && ov->tcol) rc = sph_csv_eval(&t, ov->tcol, dst->t, err);
    for (size_t r = 0; !rc && r < t.nrow; r++) {
      dst->x[r] *= ov->xscale;
      dst->y[r] *= ov->yscale;
    }
    dst->line = ov->line;
    dst->label = ov->label;
    sph_csv_free(&t);
    if (rc) return -1;
  }
  p->style.overlays = p->overlay;
  p->style.n_overlays = o->n_overlays;
  return 0;
}

static void *worker_init(void *ctx, sph_error *err) {
  plan *p = ctx;
  worker *w = calloc(1, sizeof *w);
  if (!w) {
    sph_error_set(err, "out of memory");
    return NULL;
  }
  if (rgl_context_create(p->o->backend, &w->gl, err) != 0 ||
      rcanvas_create(&w->gl->gl, p->layout.width, p->layout.height, p->o->samples, &w->canvas,
                     err) != 0) {
    rgl_context_destroy(w->gl);
    free(w);
    return NULL;
  }
  w->rgb = malloc((size_t)p->layout.width * (size_t)p->layout.height * 3);
  if (!w->rgb) {
    sph_error_set(err, "out of memory for a %dx%d image", p->layout.width, p->layout.height);
    rcanvas_destroy(w->canvas);
    rgl_context_destroy(w->gl);
    free(w);
    return NULL;
  }
  return w;
}

static void worker_fini(void *wp) {
  worker *w = wp;
  if (!w) return;
  free(w->rgb);
  rcanvas_destroy(w->canvas);
  rgl_context_destroy(w->gl);
  free(w);
}

static int run_task(void *ctx, void *wp, size_t i, sph_error *err) {
  plan *p = ctx;
  worker *w = wp;
  const rtask *t = &p->task[i];
  rsnap snaps[RLAYOUT_MAX_PANELS];
  rpanel panels[RLAYOUT_MAX_PANELS];
  memset(panels, 0, sizeof panels);
  int loaded = 0, rc = 0;
  for (int k = 0; k < t->n; k++) {
    if (rsnap_load_phases(t->path[k], p->o->field, p->o->air, &snaps[k], err) != 0) {
      rc = -1;
      break;
    }
    loaded++;
    rpanel *pa = &panels[k];
    if (p->sliced) { /* the plane's 2-D picture */
      if (((p->o->smooth || p->o->outline) && rsnap_load_volumes(&snaps[k], err) != 0) ||
          rslice_apply(&p->o->slice, &snaps[k], err) != 0) {
        rc = -1;
        break;
      }
    } else if (p->dim3) { /* the volumes: each sphere's own size, the surface */
      const int volumes = p->o->surface != RSURFACE_NONE || !(p->style.disc_size > 0.0);
      if ((volumes && rsnap_load_volumes(&snaps[k], err) != 0) ||
          draw_3d(p, w, k, &snaps[k], pa, err) != 0) {
        rc = -1;
        break;
      }
    } else if ((p->o->smooth || p->o->outline) && rsnap_load_volumes(&snaps[k], err) != 0) {
      rc = -1;
      break;
    }
    char when[64];
    rfigure_time_label(snaps[k].time, when, sizeof when);
    pa->snap = &snaps[k];
    pa->note[0] = '\0';
    if (p->sliced) { /* "t = 0.500 s, y = 0.5 m" */
      const size_t len = strlen(when);
      snprintf(when + len, sizeof when - len, ", %c = %g m", 'x' + p->o->slice.axis,
               p->o->slice.pos);
    }
    if (p->o->mode == RMODE_FRAMES) {
      snprintf(pa->label, sizeof pa->label, "%s", when);
      snprintf(pa->note, sizeof pa->note, "%s", snaps[k].case_name);
    } else if (p->o->mode == RMODE_PANELS) {
      snprintf(pa->label, sizeof pa->label, "%s %s", t->label[k], when);
    } else {
      snprintf(pa->label, sizeof pa->label, "%s", t->label[k]);
      snprintf(pa->note, sizeof pa->note, "%s", when);
    }
  }
  if (rc == 0 && rcanvas_vector_kind(t->output)) { /* SVG or PDF: cairo draws the same figure */
    rcanvas *vc = NULL;
    rc = rcanvas_create_vector(t->output, p->layout.width, p->layout.height, &vc, err);
    if (rc == 0) rc = rfigure_draw(vc, &p->layout, &p->style, panels, t->n, err);
    if (rc == 0) rc = rcanvas_finish(vc, err);
    rcanvas_destroy(vc);
  } else if (rc == 0) {
    rc = rfigure_draw(w->canvas, &p->layout, &p->style, panels, t->n, err);
    if (rc == 0) rc = rcanvas_read_rgb(w->canvas, w->rgb, err);
    if (rc == 0)
      rc = rpng_write(t->output, w->rgb, p->layout.width, p->layout.height, p->o->compression, err);
  }
  if (rc == 0 && p->o->verbose) fprintf(stderr, "wrote %s\n", t->output);
  for (int k = 0; k < loaded; k++) {
    free((void *)panels[k].image);
    rsnap_free(&snaps[k]);
  }
  return rc;
}

static void free_plan(plan *p) {
  for (size_t i = 0; i < p->n_task; i++)
    free(p->task[i].output);
  free(p->task);
  for (int i = 0; i < 16; i++) {
    free(p->overlay[i].x);
    free(p->overlay[i].y);
    free(p->overlay[i].t);
  }
  rmesh_free(&p->boxes);
  free(p->boxes_rgba);
}

static void default_size(const roptions *o, int cols, int *w, int *h) {
  *w = o->width;
  *h = o->height;
  if (*w > 0) return;
  if (o->mode == RMODE_FRAMES) {
    *w = 1280;
    *h = 720;
  } else {
    *w = (cols * 640 > 1280 ? cols * 640 : 1280) + 120;
    *h = 0;
  }
}

int rsequence_run(const roptions *o, const char *prog, sph_error *err) {
  plan p;
  memset(&p, 0, sizeof p);
  p.o = o;
  int rc = -1;
  int n_lists = o->mode == RMODE_COMPARE ? o->n_inputs : 1;
  rinputs *lists = calloc((size_t)n_lists, sizeof *lists);
  if (!lists) return sph_error_set(err, "out of memory");
  if (rfont_init(err) != 0) goto done; /* before the workers: one message */
  const char *cmap = o->cmap ? o->cmap : rsnap_signed(o->field) ? "coolwarm" : "viridis";
  if (rcolormap_get(cmap, &p.cmap, err) != 0) goto done;
  for (int i = 0; i < o->n_inputs; i++)
    if (rinputs_add(&lists[o->mode == RMODE_COMPARE ? i : 0], o->inputs[i], err) != 0) goto done;
  int cols = 1, rows = 1;
  if (o->mode == RMODE_FRAMES) {
    if (plan_frames(&p, &lists[0], err) != 0) goto done;
  } else if (o->mode == RMODE_PANELS) {
    cols = o->cols;
    rows = o->rows;
    if (plan_panels(&p, &lists[0], err) != 0) goto done;
  } else {
    if (n_lists < 2) {
      sph_error_set(err, "--compare needs two or more run directories");
      goto done;
    }
    if (n_lists > RLAYOUT_MAX_PANELS) {
      sph_error_set(err, "--compare takes at most %d runs", RLAYOUT_MAX_PANELS);
      goto done;
    }
    if (plan_compare(&p, lists, n_lists, err) != 0) goto done;
  }

  p.style.cmap = &p.cmap;
  p.style.bg = o->bg;
  p.style.fg = rmark_ink(o->bg);
  p.style.wall = (rcolor){150, 150, 150, 255};
  p.style.disc_size = o->disc_size;
  p.style.disc_scale = o->disc_scale;
  p.style.grow_small = !o->disc_given;
  p.style.walls = o->walls;
  p.style.overlay_tol = o->overlay_tol;
  p.style.title = o->title;
  p.style.smooth = o->smooth;
  p.style.outline = o->outline;
  /* a PDF or SVG: the interpolated field and the outline at --dpi */
  p.style.raster = o->output && rcanvas_vector_kind(o->output) ? o->dpi / 72.0 : 1.0;
  char units[32];
  if (rsnap_units(p.task[0].path[0], o->field, units, sizeof units, err) != 0) goto done;
  rlabel_with_units(o->field, units, p.bar_label, sizeof p.bar_label);
  p.style.bar_label = p.bar_label;

  int dim = 2;
  if (sph_snapshot_file_dimension(p.task[0].path[0], &dim, err) != 0) goto done;
  p.dim3 = dim == 3;
  if (o->have_slice) {
    if (!p.dim3) {
      sph_error_set(err, "%s is 2-D: --slice cuts 3-D snapshots", p.task[0].path[0]);
      goto done;
    }
    if (o->surface != RSURFACE_NONE) {
      sph_error_set(err, "--slice and --surface: a slice is drawn in 2-D, its outline is the "
                         "surface's cut");
      goto done;
    }
    p.dim3 = 0;
    p.sliced = 1;
    const char *names[3] = {"x (m)", "y (m)", "z (m)"};
    p.style.axis_label[0] = names[rslice_axis(o->slice.axis, 0)];
    p.style.axis_label[1] = names[rslice_axis(o->slice.axis, 1)];
  }
  if (p.dim3 && o->n_overlays > 0) {
    sph_error_set(err, "%s is 3-D: --overlay draws on 2-D snapshots and slices (--slice)",
                  p.task[0].path[0]);
    goto done;
  }
  if (!p.dim3 && o->surface != RSURFACE_NONE) {
    sph_error_set(err,
                  "%s is 2-D: --surface draws the free surface of 3-D snapshots (2-D: --outline)",
                  p.task[0].path[0]);
    goto done;
  }
  if (p.dim3 && o->smooth_given && (o->smooth == 1 || o->outline == 1)) {
    sph_error_set(err,
                  "%s is 3-D: its particles are drawn as spheres or its free surface as a mesh "
                  "(--surface); --smooth and --outline draw 2-D snapshots and slices (--slice)",
                  p.task[0].path[0]);
    goto done;
  }
  double view[4];
  if (plan_range_and_view(&p, view, err) != 0) goto done;
  if (o->mode == RMODE_COMPARE) {
    /* side by side, or stacked when the view is wide */
    int stack = (view[1] - view[0]) > 1.6 * (view[3] - view[2]);
    cols = o->cols > 0 ? o->cols : stack ? 1 : n_lists;
    rows = o->cols > 0 ? o->rows : stack ? n_lists : 1;
  }
  if (load_overlays(&p, err) != 0) goto done;
  rlayout_in li;
  memset(&li, 0, sizeof li);
  default_size(o, cols, &li.width, &li.height);
  li.rows = rows;
  li.cols = cols;
  memcpy(li.view, view, sizeof li.view);
  li.scale = o->font_scale;
  li.bare = o->bare;
  /* a one-colour water surface with grey walls (or none) carries no field: no colour bar */
  li.colorbar = o->colorbar && !(p.dim3 && o->surface == RSURFACE_WATER &&
                                 !(o->walls_given && o->walls == RWALLS_FIELD));
  li.title = o->title != NULL;
  li.lo = p.style.lo;
  li.hi = p.style.hi;
  li.no_axes = p.dim3;
  if (rlayout_figure(&li, &p.layout, err) != 0) goto done;
  if (p.dim3 && plan_camera(&p, err) != 0) goto done;
  if (o->verbose) {
    char ticks[1600];
    rlayout_describe_ticks(&p.layout, ticks, sizeof ticks);
    fprintf(stderr, "%s: %s\n", prog, ticks);
  }
  if (!li.bare && !li.no_axes && (p.layout.xt.n < 3 || p.layout.yt.n < 3)) {
    const rrect *b = &p.layout.panel[0].plot;
    const int vec = o->output && rcanvas_vector_kind(o->output);
    fprintf(stderr,
            "%s: note: each panel's plot is %.0f x %.0f %s, room for %d x and %d y tick labels; "
            "for three on each axis: fewer panels across (--panels), a larger --size or a "
            "smaller --view\n",
            prog, b->x1 - b->x0, b->y1 - b->y0, vec ? "pt" : "px", p.layout.xt.n, p.layout.yt.n);
  }

  if (p.outdir && rinputs_mkdirs(p.outdir, err) != 0) goto done;
  int jobs = o->jobs > 0 ? o->jobs : rjobs_cpus();
  const rjobs_ops ops = {worker_init, run_task, worker_fini};
  size_t failed = rjobs_run(p.n_task, jobs, &ops, &p, prog);
  if (failed) {
    sph_error_set(err, "%zu of %zu images failed", failed, p.n_task);
    rc = 1;
  } else {
    rc = 0;
    if (o->verbose || p.n_task > 1)
      fprintf(stderr, "%s: wrote %zu image%s (%s, %dx%d, %s %g:%g%s%s)\n", prog, p.n_task,
              p.n_task == 1 ? "" : "s", p.n_task == 1 ? p.task[0].output : o->output,
              p.layout.width, p.layout.height, o->field, p.style.lo, p.style.hi,
              units[0] ? " " : "", units);
  }
done:
  free_plan(&p);
  for (int i = 0; i < n_lists; i++)
    rinputs_free(&lists[i]);
  free(lists);
  return rc;
}
