/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_snapshot.c - HDF5 snapshots and the XDMF index.
 *
 * A store of a few hundred particles with varied (and awkward: -0, tiny,
 * huge, negative) values is shuffled out of id order, written, and read
 * back: every field must come back bitwise identical in id order, with the
 * header unchanged. Two writes of the same data, a second apart, must give
 * byte-identical files (no timestamps), and no ".tmp" may be left behind.
 * Broken inputs (missing, garbage, truncated files, a missing attribute, a
 * dataset of the wrong length, an absent field) must fail with a message
 * naming the file and the culprit.
 */
#include "config.h"

#include <dirent.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/particles.h"
#include "core/version.h"
#include "io/snapshot.h"
#include "testutil.h"

#define N_TEST 347

static const char CASE_TEXT[] = "name: test\n"
                                "tank: {width: 1.61, height: 0.8}\n"
                                "# a comment with <xml> & \"quotes\"\n";

static sph_snapshot_meta test_meta(int free_surface) {
  sph_snapshot_meta m;
  memset(&m, 0, sizeof m);
  m.time = 0.15625;
  m.dt = 1.25e-5;
  m.step = 12500;
  m.case_name = "test_case";
  m.case_text = CASE_TEXT;
  m.overrides = NULL;
  m.parameters = "c0: 35\nalpha: 0.1\n";
  m.dx = 0.01;
  m.h = 0.013;
  m.rho0 = 1000.0;
  m.view[0] = -0.1;
  m.view[1] = 1.7;
  m.view[2] = -0.1;
  m.view[3] = 0.9;
  m.free_surface = free_surface;
  return m;
}

/* A deterministic pseudo-random sequence (64-bit LCG). */
static uint64_t lcg(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return *s >> 11;
}

static double uniform(uint64_t *s) { return (double)lcg(s) / 9007199254740992.0; }

/* Builds n particles in id order with varied values, then shuffles them. */
static void build_store(sph_particles *p, size_t n) {
  sph_error err;
  uint64_t s = 12345;
  CU_ASSERT_FATAL(sph_particles_init(p, 8, &err) == 0);
  for (size_t i = 0; i < n; i++) {
    int32_t kind = (i % 5 == 0) ? SPH_KIND_WALL : SPH_KIND_FLUID;
    long k = sph_particles_add(p, uniform(&s) * 1.6, uniform(&s) * 0.8, uniform(&s) - 0.5,
                               -uniform(&s), 1000.0 + uniform(&s), 0.1, 0.013, kind, &err);
    CU_ASSERT_FATAL(k == (long)i);
    p->p[i] = (uniform(&s) - 0.3) * 1e4;
    p->u[i] = uniform(&s) * 1e-3;
    p->flags[i] = (uint8_t)(lcg(&s) & 3u); /* bit 1 must not leak into the file */
  }
  p->vx[0] = -0.0;
  p->p[1] = 4.9e-324; /* subnormal */
  p->u[2] = 1.7976931348623157e308;
  p->x[3] = -1e-300;
  /* shuffle the storage order */
  size_t *perm = malloc(n * sizeof *perm);
  void *work = malloc(n * sizeof(double));
  CU_ASSERT_FATAL(perm && work);
  for (size_t i = 0; i < n; i++)
    perm[i] = i;
  for (size_t i = n; i > 1; i--) {
    size_t j = (size_t)(lcg(&s) % i), t = perm[i - 1];
    perm[i - 1] = perm[j];
    perm[j] = t;
  }
  sph_particles_permute(p, perm, work);
  free(perm);
  free(work);
}

/* q = p in id order. */
static void sort_by_id(const sph_particles *p, sph_particles *q) {
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(q, p->n, &err) == 0);
  q->n = p->n;
  for (size_t i = 0; i < p->n; i++) {
    size_t k = (size_t)p->id[i];
    q->x[k] = p->x[i];
    q->y[k] = p->y[i];
    q->vx[k] = p->vx[i];
    q->vy[k] = p->vy[i];
    q->rho[k] = p->rho[i];
    q->p[k] = p->p[i];
    q->mass[k] = p->mass[i];
    q->h[k] = p->h[i];
    q->u[k] = p->u[i];
    q->kind[k] = p->kind[i];
    q->id[k] = p->id[i];
    q->flags[k] = p->flags[i];
  }
}

static char *join(const char *dir, const char *name) {
  size_t len = strlen(dir) + strlen(name) + 2;
  char *s = malloc(len);
  CU_ASSERT_FATAL(s != NULL);
  snprintf(s, len, "%s/%s", dir, name);
  return s;
}

static int file_exists(const char *path) { return access(path, F_OK) == 0; }

/* No name ending in ".tmp" in dir. */
static int no_tmp_files(const char *dir) {
  DIR *d = opendir(dir);
  struct dirent *e;
  int ok = 1;
  if (!d) return 0;
  while ((e = readdir(d)) != NULL) {
    size_t len = strlen(e->d_name);
    if (len >= 4 && strcmp(e->d_name + len - 4, ".tmp") == 0) ok = 0;
  }
  closedir(d);
  return ok;
}

static void spit(const char *path, const void *data, size_t len) {
  FILE *f = fopen(path, "wb");
  CU_ASSERT_FATAL(f != NULL);
  CU_ASSERT(fwrite(data, 1, len, f) == len);
  fclose(f);
}

#define SAME_BITS(a, b, n) (memcmp((a), (b), (n) * sizeof *(a)) == 0)

static void check_text(const sph_snapshot *s, const char *name, const char *want) {
  const char *got = sph_snapshot_text(s, name);
  CU_ASSERT_PTR_NOT_NULL_FATAL(got);
  CU_ASSERT_STRING_EQUAL(got, want);
}

static void test_round_trip(void) {
  char *dir = sph_test_tmpdir();
  char *path = join(dir, "snap.h5");
  sph_particles p, q, r;
  sph_error err;
  build_store(&p, N_TEST);
  sort_by_id(&p, &q);
  sph_snapshot_meta m = test_meta(1);
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);

  sph_snapshot *s;
  int rc = sph_snapshot_open(path, &s, &err);
  if (rc) fprintf(stderr, "%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT_STRING_EQUAL(sph_snapshot_path(s), path);
  CU_ASSERT(sph_snapshot_time(s) == m.time);
  CU_ASSERT(sph_snapshot_dt(s) == m.dt);
  CU_ASSERT(sph_snapshot_step(s) == m.step);
  CU_ASSERT(sph_snapshot_count(s) == N_TEST);
  check_text(s, "case_name", "test_case");
  check_text(s, "case_text", CASE_TEXT);
  check_text(s, "overrides", "");
  check_text(s, "parameters", m.parameters);
  check_text(s, "version", sph_version());
  check_text(s, "configure_args", sph_configure_args());
  check_text(s, "compiler", sph_compiler());
  CU_ASSERT_PTR_NULL(sph_snapshot_text(s, "no_such_text"));
  double v[4];
  CU_ASSERT(sph_snapshot_number(s, "dx", v, 1, &err) == 0 && v[0] == m.dx);
  CU_ASSERT(sph_snapshot_number(s, "h", v, 1, &err) == 0 && v[0] == m.h);
  CU_ASSERT(sph_snapshot_number(s, "rho0", v, 1, &err) == 0 && v[0] == m.rho0);
  CU_ASSERT(sph_snapshot_number(s, "view", v, 4, &err) == 0 && SAME_BITS(v, m.view, 4));
  CU_ASSERT(sph_snapshot_number(s, "view", v, 1, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "view"));
  CU_ASSERT(sph_snapshot_number(s, "nothing", v, 1, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "nothing"));

  /* fields in writing order */
  static const char *const names[] = {"x",    "y", "vx", "vy",   "rho", "p",
                                      "mass", "h", "u",  "kind", "id",  "free_surface"};
  CU_ASSERT_FATAL(sph_snapshot_field_count(s) == 12);
  for (size_t i = 0; i < 12; i++)
    CU_ASSERT_STRING_EQUAL(sph_snapshot_field_name(s, i), names[i]);
  CU_ASSERT_PTR_NULL(sph_snapshot_field_name(s, 12));

  rc = sph_snapshot_read_particles(s, &r, &err);
  if (rc) fprintf(stderr, "%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT_FATAL(r.n == N_TEST);
  CU_ASSERT(SAME_BITS(r.x, q.x, N_TEST));
  CU_ASSERT(SAME_BITS(r.y, q.y, N_TEST));
  CU_ASSERT(SAME_BITS(r.vx, q.vx, N_TEST));
  CU_ASSERT(SAME_BITS(r.vy, q.vy, N_TEST));
  CU_ASSERT(SAME_BITS(r.rho, q.rho, N_TEST));
  CU_ASSERT(SAME_BITS(r.p, q.p, N_TEST));
  CU_ASSERT(SAME_BITS(r.mass, q.mass, N_TEST));
  CU_ASSERT(SAME_BITS(r.h, q.h, N_TEST));
  CU_ASSERT(SAME_BITS(r.u, q.u, N_TEST));
  CU_ASSERT(SAME_BITS(r.kind, q.kind, N_TEST));
  CU_ASSERT(SAME_BITS(r.id, q.id, N_TEST));
  CU_ASSERT(signbit(r.vx[0]) && r.vx[0] == 0.0);
  int flags_ok = 1;
  for (size_t k = 0; k < N_TEST; k++)
    flags_ok &= r.flags[k] == (q.flags[k] & 1u);
  CU_ASSERT(flags_ok);

  /* read_field converts every type to double */
  double *f = malloc(N_TEST * sizeof *f);
  CU_ASSERT_FATAL(f != NULL);
  CU_ASSERT(sph_snapshot_read_field(s, "rho", f, &err) == 0 && SAME_BITS(f, q.rho, N_TEST));
  int kind_ok = 1, fs_ok = 1, id_ok = 1;
  CU_ASSERT(sph_snapshot_read_field(s, "kind", f, &err) == 0);
  for (size_t k = 0; k < N_TEST; k++)
    kind_ok &= f[k] == (double)q.kind[k];
  CU_ASSERT(sph_snapshot_read_field(s, "free_surface", f, &err) == 0);
  for (size_t k = 0; k < N_TEST; k++)
    fs_ok &= f[k] == (double)(q.flags[k] & 1u);
  CU_ASSERT(sph_snapshot_read_field(s, "id", f, &err) == 0);
  for (size_t k = 0; k < N_TEST; k++)
    id_ok &= f[k] == (double)k;
  CU_ASSERT(kind_ok && fs_ok && id_ok);
  free(f);

  sph_snapshot_close(s);
  sph_particles_free(&p);
  sph_particles_free(&q);
  sph_particles_free(&r);
  CU_ASSERT(no_tmp_files(dir));
  free(path);
  sph_test_rmtree(dir);
  free(dir);
}

static void test_deterministic(void) {
  char *dir = sph_test_tmpdir();
  char *a = join(dir, "a.h5"), *b = join(dir, "b.h5");
  sph_particles p;
  sph_error err;
  build_store(&p, N_TEST);
  sph_snapshot_meta m = test_meta(1);
  CU_ASSERT_FATAL(sph_snapshot_write(a, &m, &p, &err) == 0);
  sleep(1); /* HDF5 timestamps have one-second resolution */
  CU_ASSERT_FATAL(sph_snapshot_write(b, &m, &p, &err) == 0);
  size_t la = 0, lb = 0;
  char *da = sph_test_read_file(a, &la), *db = sph_test_read_file(b, &lb);
  CU_ASSERT_FATAL(da && db);
  CU_ASSERT(la == lb && la > 0 && memcmp(da, db, la) == 0);
  free(da);
  free(db);
  /* rewriting over an existing file works and leaves no tmp */
  CU_ASSERT(sph_snapshot_write(a, &m, &p, &err) == 0);
  CU_ASSERT(no_tmp_files(dir));
  sph_particles_free(&p);
  free(a);
  free(b);
  sph_test_rmtree(dir);
  free(dir);
}

/* Particle data and restart datasets carry Fletcher-32 checksums and the
 * file's metadata its own (issue 21, D9): a single flipped bit anywhere in
 * a snapshot either makes reading fail with a one-line message or leaves
 * everything read unchanged; it never changes a value silently. Every
 * 37th byte is tried. */
static void test_checksums(void) {
  char *dir = sph_test_tmpdir();
  char *path = join(dir, "snap.h5"), *bad = join(dir, "bad.h5");
  sph_particles p, q;
  sph_error err;
  build_store(&p, N_TEST);
  sph_snapshot_meta m = test_meta(1);
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  sph_snapshot *s;
  CU_ASSERT_FATAL(sph_snapshot_open(path, &s, &err) == 0);
  CU_ASSERT_FATAL(sph_snapshot_read_particles(s, &q, &err) == 0);
  sph_snapshot_close(s);
  size_t len = 0;
  char *data = sph_test_read_file(path, &len);
  CU_ASSERT_FATAL(data != NULL);
  int failed = 0, same = 0, silent = 0, multiline = 0;
  for (size_t off = 0; off < len; off += 37) {
    data[off] ^= 0x10;
    spit(bad, data, len);
    data[off] ^= 0x10;
    sph_particles r;
    if (sph_snapshot_open(bad, &s, &err)) {
      failed++;
      multiline += strchr(err.msg, '\n') != NULL;
      continue;
    }
    const int rc = sph_snapshot_read_particles(s, &r, &err);
    sph_snapshot_close(s);
    if (rc) {
      failed++;
      multiline += strchr(err.msg, '\n') != NULL;
      continue;
    }
    const size_t n = q.n;
    const int equal = r.n == n && SAME_BITS(r.x, q.x, n) && SAME_BITS(r.y, q.y, n) &&
                      SAME_BITS(r.vx, q.vx, n) && SAME_BITS(r.vy, q.vy, n) &&
                      SAME_BITS(r.rho, q.rho, n) && SAME_BITS(r.p, q.p, n) &&
                      SAME_BITS(r.mass, q.mass, n) && SAME_BITS(r.h, q.h, n) &&
                      SAME_BITS(r.kind, q.kind, n) && SAME_BITS(r.id, q.id, n);
    if (equal)
      same++;
    else if (silent++ < 5)
      printf("\n  a flipped bit at byte %zu changed the particles silently", off);
    sph_particles_free(&r);
  }
  printf("\n  %zu-byte snapshot, one bit flipped at every 37th byte: %d failed to read, "
         "%d read the same, %d changed silently",
         len, failed, same, silent);
  CU_ASSERT(silent == 0);
  CU_ASSERT(multiline == 0);
  CU_ASSERT(failed > 0);
  free(data);
  sph_particles_free(&p);
  sph_particles_free(&q);
  free(path);
  free(bad);
  sph_test_rmtree(dir);
  free(dir);
}

/* A snapshot written before the checksums (tests/data/snapshot_unchecked_v0.h5,
 * by commit cddd955: contiguous datasets, the HDF5 1.8 file format) still
 * opens and reads, restart record included. */
static void test_unchecked_still_read(void) {
  sph_snapshot *s;
  sph_error err;
  const int rc = sph_snapshot_open(sph_test_src("tests/data/snapshot_unchecked_v0.h5"), &s, &err);
  if (rc) printf("\n%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  sph_particles q;
  CU_ASSERT_FATAL(sph_snapshot_read_particles(s, &q, &err) == 0);
  CU_ASSERT(q.n > 0 && sph_snapshot_count(s) == q.n);
  sph_snapshot_restart_data rd;
  CU_ASSERT(sph_snapshot_read_restart(s, &rd, &err) == 0);
  CU_ASSERT(rd.count == q.n);
  sph_snapshot_restart_free(&rd);
  sph_particles_free(&q);
  sph_snapshot_close(s);
}

static void test_free_surface_optional(void) {
  char *dir = sph_test_tmpdir();
  char *path = join(dir, "nofs.h5");
  sph_particles p, r;
  sph_error err;
  build_store(&p, N_TEST);
  sph_snapshot_meta m = test_meta(0);
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  sph_snapshot *s;
  CU_ASSERT_FATAL(sph_snapshot_open(path, &s, &err) == 0);
  CU_ASSERT(sph_snapshot_field_count(s) == 11);
  CU_ASSERT(!sph_snapshot_has_field(s, "free_surface"));
  CU_ASSERT(sph_snapshot_has_field(s, "u"));
  double *f = malloc(N_TEST * sizeof *f);
  CU_ASSERT_FATAL(f != NULL);
  err.msg[0] = '\0';
  CU_ASSERT(sph_snapshot_read_field(s, "free_surface", f, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "free_surface"));
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, path));
  free(f);
  CU_ASSERT_FATAL(sph_snapshot_read_particles(s, &r, &err) == 0);
  int zero = 1;
  for (size_t k = 0; k < r.n; k++)
    zero &= r.flags[k] == 0;
  CU_ASSERT(zero);
  sph_particles_free(&r);
  sph_snapshot_close(s);
  sph_particles_free(&p);
  free(path);
  sph_test_rmtree(dir);
  free(dir);
}

/* The group /geometry: what is written reads back to the bit (a tank,
 * two obstacles, a wall, three probes), two writes are byte-identical, a
 * snapshot without the group (written before it existed) says so with 1,
 * and a group of another format is refused by name. */
static void test_geometry(void) {
  char *dir = sph_test_tmpdir();
  char *a = join(dir, "geo_a.h5"), *b = join(dir, "geo_b.h5");
  sph_particles p;
  sph_error err;
  build_store(&p, N_TEST);
  double obstacles[2][6] = {{0.1, 0.2, 0.3, 0.4, 0.5, 0.6}, {1.5, 2.5, 0.0, 0.25, 0, 0}};
  double walls[1][6] = {{0.0, -0.01, 0.2, -0.01, 0, 0}};
  double at[3][3] = {{0.5, 0.25, 0}, {1.0, 0, 0}, {0.125, 0.375, 0}};
  char names[3][SPH_GEOMETRY_NAME] = {"P1", "H1", "a_probe.name-2"};
  char kinds[3][SPH_GEOMETRY_KIND] = {"pressure", "level", "velocity"};
  sph_snapshot_geometry g = {.dim = SPH_DIM,
                             .has_tank = 1,
                             .tank = {0.0, 1.61, 0.0, 0.6, 0, 0},
                             .n_obstacles = 2,
                             .obstacles = obstacles,
                             .n_walls = 1,
                             .walls = walls,
                             .n_probes = 3,
                             .probe_position = at,
                             .probe_name = names,
                             .probe_kind = kinds};
  sph_snapshot_meta m = test_meta(0);
  m.geometry = &g;
  CU_ASSERT_FATAL(sph_snapshot_write(a, &m, &p, &err) == 0);
  sleep(1); /* HDF5 timestamps have one-second resolution */
  CU_ASSERT_FATAL(sph_snapshot_write(b, &m, &p, &err) == 0);
  size_t la = 0, lb = 0;
  char *da = sph_test_read_file(a, &la), *db = sph_test_read_file(b, &lb);
  CU_ASSERT(da && db && la == lb && la > 0 && memcmp(da, db, la) == 0);
  free(da);
  free(db);
  sph_snapshot *s;
  CU_ASSERT_FATAL(sph_snapshot_open(a, &s, &err) == 0);
  sph_snapshot_geometry r;
  const int rc = sph_snapshot_read_geometry(s, &r, &err);
  if (rc) printf("\n%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT(r.dim == SPH_DIM && r.has_tank == 1);
  CU_ASSERT(memcmp(r.tank, g.tank, 2 * SPH_DIM * sizeof(double)) == 0);
  CU_ASSERT_FATAL(r.n_obstacles == 2 && r.n_walls == 1 && r.n_probes == 3);
  for (int k = 0; k < 2; k++)
    CU_ASSERT(memcmp(r.obstacles[k], obstacles[k], 2 * SPH_DIM * sizeof(double)) == 0);
  CU_ASSERT(memcmp(r.walls[0], walls[0], 2 * SPH_DIM * sizeof(double)) == 0);
  for (int k = 0; k < 3; k++) {
    CU_ASSERT(memcmp(r.probe_position[k], at[k], SPH_DIM * sizeof(double)) == 0);
    CU_ASSERT_STRING_EQUAL(r.probe_name[k], names[k]);
    CU_ASSERT_STRING_EQUAL(r.probe_kind[k], kinds[k]);
  }
  sph_snapshot_geometry_free(&r);
  CU_ASSERT(r.obstacles == NULL && r.n_probes == 0);
  sph_snapshot_close(s);
  /* a snapshot without the group: 1, and *g empty */
  m.geometry = NULL;
  CU_ASSERT_FATAL(sph_snapshot_write(b, &m, &p, &err) == 0);
  CU_ASSERT_FATAL(sph_snapshot_open(b, &s, &err) == 0);
  CU_ASSERT(sph_snapshot_read_geometry(s, &r, &err) == 1);
  CU_ASSERT(r.n_obstacles == 0 && r.obstacles == NULL && !r.has_tank);
  sph_snapshot_close(s);
  CU_ASSERT_FATAL(
      sph_snapshot_open(sph_test_src("tests/data/snapshot_unchecked_v0.h5"), &s, &err) == 0);
  CU_ASSERT(sph_snapshot_read_geometry(s, &r, &err) == 1);
  sph_snapshot_close(s);
  /* another format: refused, naming it */
  char cmd[4096];
  snprintf(cmd, sizeof cmd,
           "python3 -c \"import h5py; f = h5py.File('%s', 'r+'); "
           "f['geometry'].attrs.modify('format', 7)\" 2>/dev/null || "
           "/usr/bin/python3 -c \"import h5py; f = h5py.File('%s', 'r+'); "
           "f['geometry'].attrs.modify('format', 7)\"",
           a, a);
  CU_ASSERT_FATAL(sph_test_system(cmd) == 0);
  CU_ASSERT_FATAL(sph_snapshot_open(a, &s, &err) == 0);
  CU_ASSERT(sph_snapshot_read_geometry(s, &r, &err) == -1);
  CU_ASSERT(strstr(err.msg, "the group /geometry has format 7") != NULL);
  sph_snapshot_close(s);
  sph_particles_free(&p);
  free(a);
  free(b);
  sph_test_rmtree(dir);
  free(dir);
}

static void test_empty_store(void) {
  char *dir = sph_test_tmpdir();
  char *path = join(dir, "empty.h5");
  sph_particles p, r;
  sph_error err;
  CU_ASSERT_FATAL(sph_particles_init(&p, 0, &err) == 0);
  sph_snapshot_meta m = test_meta(1);
  int rc = sph_snapshot_write(path, &m, &p, &err);
  if (rc) fprintf(stderr, "%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  sph_snapshot *s;
  CU_ASSERT_FATAL(sph_snapshot_open(path, &s, &err) == 0);
  CU_ASSERT(sph_snapshot_count(s) == 0);
  CU_ASSERT(sph_snapshot_field_count(s) == 12);
  CU_ASSERT(sph_snapshot_read_particles(s, &r, &err) == 0 && r.n == 0);
  sph_particles_free(&r);
  sph_snapshot_close(s);
  sph_particles_free(&p);
  free(path);
  sph_test_rmtree(dir);
  free(dir);
}

static void test_bad_ids(void) {
  char *dir = sph_test_tmpdir();
  char *path = join(dir, "bad.h5");
  sph_particles p;
  sph_error err;
  build_store(&p, 20);
  p.id[7] = p.id[3];
  sph_snapshot_meta m = test_meta(0);
  CU_ASSERT(sph_snapshot_write(path, &m, &p, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "duplicate"));
  CU_ASSERT(!file_exists(path));
  m.case_name = NULL;
  CU_ASSERT(sph_snapshot_write(path, &m, &p, &err) != 0);
  CU_ASSERT(no_tmp_files(dir));
  sph_particles_free(&p);
  free(path);
  sph_test_rmtree(dir);
  free(dir);
}

static void test_write_failure(void) {
  char *dir = sph_test_tmpdir();
  char *path = join(dir, "no/such/dir/snap.h5");
  sph_particles p;
  sph_error err;
  build_store(&p, 10);
  sph_snapshot_meta m = test_meta(0);
  err.msg[0] = '\0';
  CU_ASSERT(sph_snapshot_write(path, &m, &p, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, path));
  CU_ASSERT(no_tmp_files(dir));
  sph_particles_free(&p);
  free(path);
  sph_test_rmtree(dir);
  free(dir);
}

/* Opening path must fail with a message naming the file and want. */
static void expect_open_failure(const char *path, const char *want) {
  sph_snapshot *s = (sph_snapshot *)&s;
  sph_error err;
  err.msg[0] = '\0';
  CU_ASSERT(sph_snapshot_open(path, &s, &err) != 0);
  CU_ASSERT_PTR_NULL(s);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, path));
  if (want) CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, want));
  if (!strstr(err.msg, path) || (want && !strstr(err.msg, want)))
    fprintf(stderr, "unexpected message: %s\n", err.msg);
}

static void test_bad_files(void) {
  char *dir = sph_test_tmpdir();
  char *missing = join(dir, "missing.h5"), *garbage = join(dir, "garbage.h5");
  char *good = join(dir, "good.h5"), *cut = join(dir, "cut.h5");
  sph_particles p;
  sph_error err;

  expect_open_failure(missing, NULL);

  unsigned char junk[4096];
  uint64_t st = 99;
  for (size_t i = 0; i < sizeof junk; i++)
    junk[i] = (unsigned char)lcg(&st);
  spit(garbage, junk, sizeof junk);
  expect_open_failure(garbage, "not an HDF5 file");
  spit(garbage, "", 0);
  expect_open_failure(garbage, NULL);

  build_store(&p, N_TEST);
  sph_snapshot_meta m = test_meta(1);
  CU_ASSERT_FATAL(sph_snapshot_write(good, &m, &p, &err) == 0);
  size_t len;
  char *data = sph_test_read_file(good, &len);
  CU_ASSERT_FATAL(data != NULL);
  for (size_t keep = len / 2; keep > 0; keep /= 4) { /* truncated at several lengths */
    spit(cut, data, keep);
    expect_open_failure(cut, NULL);
  }
  free(data);
  sph_particles_free(&p);
  free(missing);
  free(garbage);
  free(good);
  free(cut);
  sph_test_rmtree(dir);
  free(dir);
}

/* Edits a good snapshot with the HDF5 API to break it in one place. */
static void test_broken_contents(void) {
  char *dir = sph_test_tmpdir();
  char *path = join(dir, "edit.h5");
  sph_particles p;
  sph_error err;
  build_store(&p, 50);
  sph_snapshot_meta m = test_meta(0);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);

  /* a dataset of the wrong length */
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CU_ASSERT_FATAL(f >= 0);
  CU_ASSERT(H5Ldelete(f, "/particles/vy", H5P_DEFAULT) >= 0);
  hsize_t dims[1] = {49};
  hid_t sp = H5Screate_simple(1, dims, NULL);
  hid_t d =
      H5Dcreate2(f, "/particles/vy", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CU_ASSERT(d >= 0);
  H5Dclose(d);
  H5Sclose(sp);
  H5Fclose(f);
  expect_open_failure(path, "/particles/vy");

  /* a missing attribute */
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CU_ASSERT_FATAL(f >= 0);
  CU_ASSERT(H5Adelete(f, "dt") >= 0);
  H5Fclose(f);
  expect_open_failure(path, "\"dt\"");

  /* no /particles group */
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CU_ASSERT_FATAL(f >= 0);
  CU_ASSERT(H5Ldelete(f, "/particles", H5P_DEFAULT) >= 0);
  H5Fclose(f);
  expect_open_failure(path, "/particles");

  /* a missing mandatory dataset: open succeeds, reading the store fails */
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CU_ASSERT_FATAL(f >= 0);
  CU_ASSERT(H5Ldelete(f, "/particles/mass", H5P_DEFAULT) >= 0);
  H5Fclose(f);
  sph_snapshot *s;
  CU_ASSERT_FATAL(sph_snapshot_open(path, &s, &err) == 0);
  sph_particles r;
  CU_ASSERT(sph_snapshot_read_particles(s, &r, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, "mass"));
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, path));
  sph_snapshot_close(s);

  /* fixed-length strings (as other tools write them) are read too */
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CU_ASSERT_FATAL(f >= 0);
  CU_ASSERT(H5Adelete(f, "case_name") >= 0);
  CU_ASSERT(H5Adelete(f, "version") >= 0);
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, 12);
  H5Tset_strpad(t, H5T_STR_SPACEPAD);
  sp = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(f, "case_name", t, sp, H5P_DEFAULT, H5P_DEFAULT);
  CU_ASSERT(a >= 0 && H5Awrite(a, t, "fixed name  ") >= 0);
  H5Aclose(a);
  H5Sclose(sp);
  H5Tclose(t);
  H5Fclose(f);
  CU_ASSERT_FATAL(sph_snapshot_open(path, &s, &err) == 0);
  CU_ASSERT_STRING_EQUAL(sph_snapshot_text(s, "case_name"), "fixed name");
  CU_ASSERT_PTR_NULL(sph_snapshot_text(s, "version")); /* optional */
  sph_snapshot_close(s);

  /* a 3-D snapshot (its "dimension" 3) is refused by the 2-D library, by name */
  CU_ASSERT_FATAL(sph_snapshot_write(path, &m, &p, &err) == 0);
  f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CU_ASSERT_FATAL(f >= 0);
  const int64_t three = 3;
  sp = H5Screate(H5S_SCALAR);
  a = H5Acreate2(f, "dimension", H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  CU_ASSERT(a >= 0 && H5Awrite(a, H5T_NATIVE_INT64, &three) >= 0);
  H5Aclose(a);
  H5Sclose(sp);
  H5Fclose(f);
  expect_open_failure(path, "a 3-D snapshot");

  sph_particles_free(&p);
  free(path);
  sph_test_rmtree(dir);
  free(dir);
}

static int contains(const char *text, const char *what) { return strstr(text, what) != NULL; }

static void test_xdmf(void) {
  char *dir = sph_test_tmpdir();
  char *xmf = join(dir, "run.xmf");
  sph_particles p;
  sph_error err;
  build_store(&p, 30);
  const char *names[3] = {"snap_000000.h5", "snap_000100.h5", "snap_000200.h5"};
  const double times[3] = {0.0, 0.1, 0.30000000000000004};
  for (int i = 0; i < 3; i++) {
    char *h5 = join(dir, names[i]);
    sph_snapshot_meta m = test_meta(1);
    m.time = times[i];
    CU_ASSERT_FATAL(sph_snapshot_write(h5, &m, &p, &err) == 0);
    free(h5);
  }
  const size_t counts[3] = {p.n, p.n, p.n};
  int rc = sph_xdmf_write(xmf, 3, names, times, counts, 1, &err);
  if (rc) fprintf(stderr, "%s\n", err.msg);
  CU_ASSERT_FATAL(rc == 0);
  CU_ASSERT(no_tmp_files(dir));
  size_t len;
  char *text = sph_test_read_file(xmf, &len);
  CU_ASSERT_FATAL(text != NULL);
  CU_ASSERT(contains(text, "<Xdmf Version=\"3.0\">"));
  CU_ASSERT(contains(text, "GridType=\"Collection\" CollectionType=\"Temporal\""));
  CU_ASSERT(contains(text, "TopologyType=\"Polyvertex\" NumberOfElements=\"30\" "
                           "NodesPerElement=\"1\">\n          <DataItem Dimensions=\"30\" "
                           "NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">snap_000000.h5:"
                           "/particles/id</DataItem>\n        </Topology>"));
  CU_ASSERT(contains(text, "<Geometry GeometryType=\"XY\">\n          <DataItem Dimensions=\"30 "
                           "2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">snap_000000.h5:"
                           "/vectors/position</DataItem>"));
  CU_ASSERT(contains(text, "<Attribute Name=\"velocity\" AttributeType=\"Vector\" "
                           "Center=\"Node\">\n          <DataItem Dimensions=\"30 3\""));
  CU_ASSERT(contains(text, "<Time Value=\"0\"/>"));
  CU_ASSERT(contains(text, "<Time Value=\"0.10000000000000001\"/>"));
  CU_ASSERT(contains(text, "<Time Value=\"0.30000000000000004\"/>"));
  static const char *const fields[] = {"x",    "y", "vx", "vy",   "rho", "p",
                                       "mass", "h", "u",  "kind", "id",  "free_surface"};
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 12; k++) {
      char ref[128];
      snprintf(ref, sizeof ref, ">%s:/particles/%s</DataItem>", names[i], fields[k]);
      CU_ASSERT(contains(text, ref));
      snprintf(ref, sizeof ref, "<Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">",
               fields[k]);
      CU_ASSERT(contains(text, ref));
    }
  free(text);
  if (sph_test_system("command -v xmllint >/dev/null 2>&1") == 0) {
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "xmllint --noout '%s'", xmf);
    CU_ASSERT(sph_test_system(cmd) == 0);
  }

  /* without free_surface, odd characters escaped, a time that cannot be written */
  const char *odd[1] = {"a&b<c>.h5"};
  CU_ASSERT_FATAL(sph_xdmf_write(xmf, 1, odd, times, &p.n, 0, &err) == 0);
  text = sph_test_read_file(xmf, &len);
  CU_ASSERT_FATAL(text != NULL);
  CU_ASSERT(!contains(text, "free_surface"));
  CU_ASSERT(contains(text, ">a&amp;b&lt;c&gt;.h5:/particles/rho</DataItem>"));
  free(text);
  const double bad[1] = {NAN};
  CU_ASSERT(sph_xdmf_write(xmf, 1, names, bad, &p.n, 0, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, xmf));
  const char *colon[1] = {"c:snap.h5"};
  CU_ASSERT(sph_xdmf_write(xmf, 1, colon, times, &p.n, 0, &err) != 0);
  char *nowhere = join(dir, "no/dir/run.xmf");
  CU_ASSERT(sph_xdmf_write(nowhere, 3, names, times, counts, 0, &err) != 0);
  CU_ASSERT_PTR_NOT_NULL(strstr(err.msg, nowhere));
  free(nowhere);
  CU_ASSERT(no_tmp_files(dir));

  sph_particles_free(&p);
  free(xmf);
  sph_test_rmtree(dir);
  free(dir);
}

int main(void) {
  CU_TestInfo tests[] = {
      {"round trip, shuffled storage order", test_round_trip},
      {"two writes are byte-identical", test_deterministic},
      {"checksums: a flipped bit fails or changes nothing", test_checksums},
      {"snapshots without checksums are still read", test_unchecked_still_read},
      {"free_surface only when asked", test_free_surface_optional},
      {"empty store", test_empty_store},
      {"the geometry group: round trip, absent in older files", test_geometry},
      {"ids must be a permutation", test_bad_ids},
      {"unwritable path", test_write_failure},
      {"missing, garbage and truncated files", test_bad_files},
      {"wrong length, missing attribute or dataset, fixed strings", test_broken_contents},
      {"XDMF index", test_xdmf},
      CU_TEST_INFO_NULL,
  };
  return sph_test_main("snapshot", tests);
}
