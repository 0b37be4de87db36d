/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * test_restart.c - `sph run --restart SNAPSHOT CASE` continues a run
 * bitwise.
 *
 * Small cases (tests/data/restart_*.yaml) between them switch on
 * what a restart must carry over: the predictor-corrector and the
 * leap-frog (half-step values, first step), the paper B, CFL and fixed
 * step rules, an MLS and a Shepard filter (step counter), a moving gate
 * (its phase), variable h and h* on the free surface, XSPH, Morris and SPS
 * viscosity, dynamic, repulsive and mirror walls, periodic x, particle
 * shifting, the energy ledger (its integrals, shifting's drift among them), wave gauges (their
 * levels at t = 0), the pressure probes' low-pass filters (their outputs) and free-surface flags
 * read from the kept neighbour list; restart_default is the default scheme as shipped (the
 * leap-frog with a step that changes, Adami walls), restart_no_tension the same with the
 * density floor of a fluid without tension, restart_outflow fluid taken out of the run as it
 * leaves the domain (which particles left, what they carried, the snapshots' own counts in
 * the XDMF index), restart_air two phases (the air's particles, phases and laws, the walls'
 * pressure for each phase: doc/method.md, Two phases). Each is run
 * uninterrupted; then
 *   - restarted from snap_0002 (restart_fs: snap_0003) into a fresh
 *     directory (1 thread; the uninterrupted run on 2): every
 *     later snapshot equals the uninterrupted one dataset by dataset, bit
 *     for bit, restart record included, and the files are byte-identical;
 *     diagnostics.csv starts at the restart time with the same rows;
 *   - restarted in a copy of its own directory: diagnostics.csv,
 *     gauges.csv, probes.csv and snapshots.xmf come out byte-identical to the
 *     uninterrupted run's (later rows dropped, then appended again); the
 *     mirror case as `sph run --restart SNAPSHOT` alone (the case and its
 *     overrides from the snapshot, the output in its directory);
 *   - restarted from snap_0000 (the leap-frog's first step still to do).
 * Bad restarts fail with exit status 1 and a message naming the file and
 * the cause: other parameters (naming the first differing key), another
 * case, a snapshot without a restart record, a missing file, a clock out
 * of range (time.end before the snapshot, a time that is not finite or
 * negative, a negative step); time.end may change (a run is extended).
 */
#include "config.h"

#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "io/snapshot.h"
#include "snapcmp.h"
#include "testutil.h"

static char *tmp;

/* Runs `sph ARGS` (output in tmp/sph.log, returned in out). */
static int sph(const char *args, char *out, size_t len) {
  return sph_test_sph(args, tmp, out, len);
}
/* The same for a run that should succeed (its output printed if not). */
static int sph_ok(const char *args, char *out, size_t len) {
  return sph_test_sph_ok(args, tmp, out, len);
}

static const char *case_file(const char *name) {
  static char buf[4096];
  char rel[256];
  snprintf(rel, sizeof rel, "tests/data/%s.yaml", name);
  snprintf(buf, sizeof buf, "%s", sph_test_src(rel));
  return buf;
}

/* The uninterrupted run of a case into tmp/<name>.full; returns the
 * number of snapshots. */
static int full_run(const char *name) {
  char args[32768], out[65536];
  snprintf(args, sizeof args, "run -q --threads 2 '%s' -o '%s/%s.full'", case_file(name), tmp,
           name);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  int n = 0;
  for (;; n++) {
    char path[4300];
    snprintf(path, sizeof path, "%s/%s.full/snap_%04d.h5", tmp, name, n);
    FILE *f = fopen(path, "rb");
    if (!f) break;
    fclose(f);
  }
  return n;
}

/* Snapshots from..n-1 of dir equal those of the uninterrupted run. */
static void same_snapshots(const char *name, const char *dir, int from, int n) {
  for (int k = from; k < n; k++) {
    char a[4300], b[4300], what[256];
    snprintf(a, sizeof a, "%s/%s.full/snap_%04d.h5", tmp, name, k);
    snprintf(b, sizeof b, "%s/snap_%04d.h5", dir, k);
    snprintf(what, sizeof what, "%s snap_%04d", name, k);
    CU_ASSERT_EQUAL(snapcmp(what, a, b, 1), 0);
    CU_ASSERT_EQUAL(snapcmp_files(a, b), 0);
  }
}

/* Fresh directory: restart from snap_<k>, compare what follows. */
static void restart_fresh(const char *name, int k) {
  const int n = full_run(name);
  CU_ASSERT_FATAL(n > k + 2);
  char args[32768], out[65536], dir[4200];
  snprintf(dir, sizeof dir, "%s/%s.from%d", tmp, name, k);
  snprintf(args, sizeof args, "run -q --threads 1 --restart '%s/%s.full/snap_%04d.h5' '%s' -o '%s'",
           tmp, name, k, case_file(name), dir);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  same_snapshots(name, dir, k + 1, n);
  /* the restart snapshot itself is not rewritten */
  char path[4300];
  snprintf(path, sizeof path, "%s/snap_%04d.h5", dir, k);
  FILE *f = fopen(path, "rb");
  CU_ASSERT(f == NULL);
  if (f) fclose(f);
  /* diagnostics: the header, then the full run's rows from the restart time */
  snprintf(path, sizeof path, "%s/%s.full/diagnostics.csv", tmp, name);
  char *full = sph_test_read_file(path, NULL);
  snprintf(path, sizeof path, "%s/diagnostics.csv", dir);
  char *part = sph_test_read_file(path, NULL);
  CU_ASSERT_FATAL(full && part);
  char *nl = strchr(part, '\n');
  CU_ASSERT_FATAL(nl != NULL);
  const size_t hlen = (size_t)(nl - part) + 1;
  CU_ASSERT(strncmp(full, part, hlen) == 0);
  const char *rows = full + hlen;
  for (int r = 0; r < k; r++)
    rows = strchr(rows, '\n') + 1;
  CU_ASSERT_STRING_EQUAL(part + hlen, rows);
  free(full);
  free(part);
  /* probes.csv: the header, then the full run's last rows (those after the
   * restart time, and its own if one was due) */
  snprintf(path, sizeof path, "%s/%s.full/probes.csv", tmp, name);
  full = sph_test_read_file(path, NULL);
  if (!full) return; /* no probes in this case */
  snprintf(path, sizeof path, "%s/probes.csv", dir);
  part = sph_test_read_file(path, NULL);
  CU_ASSERT_FATAL(part != NULL);
  nl = strchr(part, '\n');
  CU_ASSERT_FATAL(nl != NULL);
  const size_t plen = strlen(nl + 1), flen = strlen(full);
  CU_ASSERT(strncmp(full, part, (size_t)(nl - part) + 1) == 0);
  CU_ASSERT(plen > 0 && plen < flen && strcmp(full + flen - plen, nl + 1) == 0);
  free(full);
  free(part);
}

static void test_pc_fresh(void) { restart_fresh("restart_pc", 2); }
static void test_lf_fresh(void) { restart_fresh("restart_lf", 2); }
static void test_mirror_fresh(void) { restart_fresh("restart_mirror", 2); }
static void test_lf_from_start(void) { restart_fresh("restart_lf", 0); }
static void test_fs_fresh(void) { restart_fresh("restart_fs", 3); }
static void test_adami_fresh(void) { restart_fresh("restart_adami", 2); }
static void test_default_fresh(void) { restart_fresh("restart_default", 2); }
static void test_no_tension_fresh(void) { restart_fresh("restart_no_tension", 2); }
static void test_air_fresh(void) { restart_fresh("restart_air", 2); }

/* Restart in a copy of the run's own directory (which holds the later
 * snapshots and rows already): the end result is byte for byte the
 * uninterrupted run's. With old_headers the copy's CSV headers are those
 * of a run written before they gave units ("time,step"): its rows are
 * kept and the header becomes today's. */
static void restart_in_place(const char *name, int k, int short_form, int old_headers) {
  const int n = full_run(name);
  char args[32768], out[65536], dir[4200];
  snprintf(dir, sizeof dir, "%s/%s.copy", tmp, name);
  snprintf(args, sizeof args, "rm -rf '%s' && cp -r '%s/%s.full' '%s'", dir, tmp, name, dir);
  CU_ASSERT_FATAL(sph_test_system(args) == 0);
  /* a torn last row, as a killed run may leave, is dropped too */
  snprintf(args, sizeof args, "printf '0.99,12' >> '%s/diagnostics.csv'", dir);
  CU_ASSERT_FATAL(sph_test_system(args) == 0);
  if (old_headers == 2) { /* CRLF line ends, as a spreadsheet may save them (issue 61, E6) */
    snprintf(args, sizeof args, "cd '%s' && sed -i 's/$/\\r/' diagnostics.csv", dir);
    CU_ASSERT_FATAL(sph_test_system(args) == 0);
  } else if (old_headers) {
    snprintf(args, sizeof args,
             "cd '%s' && for f in diagnostics.csv gauges.csv probes.csv; do [ ! -f $f ] || "
             "sed -i '1s/ ([^)]*)//g' $f; done && head -n 1 diagnostics.csv | grep -qv '('",
             dir);
    CU_ASSERT_FATAL(sph_test_system(args) == 0);
  }
  if (short_form) /* the case from the snapshot, the output in its directory */
    snprintf(args, sizeof args, "run -q --restart '%s/snap_%04d.h5'", dir, k);
  else
    snprintf(args, sizeof args, "run -q --restart '%s/snap_%04d.h5' '%s' -o '%s'", dir, k,
             case_file(name), dir);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  same_snapshots(name, dir, 0, n);
  const char *files[] = {"diagnostics.csv", "gauges.csv", "probes.csv", "snapshots.xmf"};
  for (int i = 0; i < 4; i++) {
    char a[4300], b[4300];
    snprintf(a, sizeof a, "%s/%s.full/%s", tmp, name, files[i]);
    snprintf(b, sizeof b, "%s/%s", dir, files[i]);
    FILE *f = fopen(a, "rb");
    if (!f) continue; /* no gauges in this case */
    fclose(f);
    if (snapcmp_files(a, b)) printf("\n  %s differs\n", b);
    CU_ASSERT_EQUAL(snapcmp_files(a, b), 0);
  }
}

/* snap_0003 of restart_pc is at a listed output time (0.0123 s) */
static void test_pc_in_place(void) { restart_in_place("restart_pc", 3, 0, 0); }
static void test_mirror_in_place(void) { restart_in_place("restart_mirror", 4, 1, 1); }
static void test_crlf_in_place(void) { restart_in_place("restart_pc", 3, 0, 2); }
/* snap_0004 (t = 0.2 s) after 17 particles left the domain, more leave later */
static void test_outflow_fresh(void) { restart_fresh("restart_outflow", 4); }
static void test_outflow_in_place(void) { restart_in_place("restart_outflow", 4, 0, 0); }

/* A restart in place never drops rows it cannot read (issue 61, E6): a
 * file with other columns or a row whose time is not a number is refused
 * with its name and line, and every file is left as it was. */
static void test_unreadable_rows(void) {
  full_run("restart_pc");
  static const char *const edits[][3] = {
      {"diagnostics.csv", "1s/^time (s),step/time (s),steps/",
       "diagnostics.csv: its header is not the columns this case writes (line 1: 'time (s),steps"},
      {"probes.csv", "1s/,[^,]*$/,X (Pa)/", "probes.csv: its header is not the columns"},
      {"diagnostics.csv", "4s/^[^,]*,/nan,/",
       "diagnostics.csv:4: expected a row that starts with its time, got 'nan,"},
      {"diagnostics.csv", "3s/^.*$//",
       "diagnostics.csv:3: expected a row that starts with its "
       "time, got ''"}};
  for (size_t k = 0; k < sizeof edits / sizeof *edits; k++) {
    char args[32768], out[65536], dir[4200];
    snprintf(dir, sizeof dir, "%s/unreadable%zu", tmp, k);
    snprintf(args, sizeof args,
             "rm -rf '%s' && cp -r '%s/restart_pc.full' '%s' && sed -i '%s' '%s/%s' && "
             "cp -r '%s' '%s.before'",
             dir, tmp, dir, edits[k][1], dir, edits[k][0], dir, dir);
    CU_ASSERT_FATAL(sph_test_system(args) == 0);
    snprintf(args, sizeof args, "run -q --restart '%s/snap_0002.h5' '%s' -o '%s'", dir,
             case_file("restart_pc"), dir);
    CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
    const int said = strstr(out, edits[k][2]) != NULL;
    if (!said) printf("\n  want '%s' in: %s", edits[k][2], out);
    CU_ASSERT(said);
    snprintf(args, sizeof args, "diff -r '%s' '%s.before'", dir, dir);
    CU_ASSERT_EQUAL(sph_test_system(args), 0);
  }
}

static void test_bad_restarts(void) {
  full_run("restart_pc");
  char args[32768], out[65536], snap[4200];
  snprintf(snap, sizeof snap, "%s/restart_pc.full/snap_0002.h5", tmp);
  /* other parameters: the first differing key is named */
  snprintf(args, sizeof args,
           "run -q --restart '%s' '%s' -o '%s/bad1' --set physics.artificial_viscosity.alpha=0.2",
           snap, case_file("restart_pc"), tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "snap_0002.h5") != NULL);
  CU_ASSERT(strstr(out, "physics.artificial_viscosity.alpha") != NULL);
  /* another case altogether */
  snprintf(args, sizeof args, "run -q --restart '%s' '%s' -o '%s/bad2'", snap,
           case_file("restart_lf"), tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "not a snapshot of this case") != NULL ||
            strstr(out, "other parameters") != NULL);
  /* a missing file */
  snprintf(args, sizeof args, "run -q --restart '%s/nope.h5' '%s' -o '%s/bad3'", tmp,
           case_file("restart_pc"), tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "nope.h5") != NULL);
  /* a snapshot without a restart record */
  char plain[4300];
  snprintf(plain, sizeof plain, "%s/plain.h5", tmp);
  {
    sph_particles p;
    sph_error err;
    CU_ASSERT_FATAL(sph_particles_init(&p, 4, &err) == 0);
    CU_ASSERT_FATAL(sph_particles_add(&p, 0.1, 0.1, 0, 0, 1000, 0.1, 0.013, SPH_KIND_FLUID, &err) ==
                    0);
    p.id[0] = 0;
    sph_snapshot_meta m;
    memset(&m, 0, sizeof m);
    m.case_name = "restart_pc";
    CU_ASSERT_FATAL(sph_snapshot_write(plain, &m, &p, &err) == 0);
    sph_particles_free(&p);
  }
  snprintf(args, sizeof args, "run -q --restart '%s' '%s' -o '%s/bad4'", plain,
           case_file("restart_pc"), tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "plain.h5") != NULL);
  /* without a case file: a missing snapshot, one without a stored case, and
   * an override other than time.end */
  snprintf(args, sizeof args, "run -q --restart '%s/nope.h5'", tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "--restart") != NULL && strstr(out, "nope.h5") != NULL);
  snprintf(args, sizeof args, "run -q --restart '%s' -o '%s/bad5'", plain, tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "plain.h5") != NULL && strstr(out, "case_text") != NULL);
  snprintf(args, sizeof args,
           "run -q --restart '%s' -o '%s/bad6' --set physics.artificial_viscosity.alpha=0.2", snap,
           tmp);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  CU_ASSERT(strstr(out, "physics.artificial_viscosity.alpha") != NULL);
  /* no case and no --restart: usage */
  CU_ASSERT_EQUAL(sph("run -q", out, sizeof out), 2);
  /* a value missing from --restart is a usage error */
  snprintf(args, sizeof args, "run '%s' --restart", case_file("restart_pc"));
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 2);
  /* time.end may change: the run is extended past the first one's end */
  snprintf(args, sizeof args,
           "run -q --restart '%s/restart_pc.full/snap_0007.h5' '%s' -o '%s/longer' "
           "--set time.end=0.04",
           tmp, case_file("restart_pc"), tmp);
  CU_ASSERT_EQUAL(sph_ok(args, out, sizeof out), 0);
  size_t n = 0;
  double t = 0.0;
  snprintf(snap, sizeof snap, "%s/longer/snap_0009.h5", tmp);
  CU_ASSERT(snapcmp_complete(snap, &n, &t));
  CU_ASSERT_DOUBLE_EQUAL(t, 0.04, 1e-12);
  /* --help documents the flag */
  CU_ASSERT_EQUAL(sph("run --help", out, sizeof out), 0);
  CU_ASSERT(strstr(out, "--restart SNAPSHOT") != NULL);
}

/* Sets the double attribute `name` of a snapshot's root (time, dt) or,
 * with is_int, the int64 one (step). */
static void set_attribute(const char *path, const char *name, double v, int is_int) {
  const hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  CU_ASSERT_FATAL(f >= 0);
  const hid_t a = H5Aopen(f, name, H5P_DEFAULT);
  CU_ASSERT_FATAL(a >= 0);
  const int64_t iv = (int64_t)v;
  CU_ASSERT(is_int ? H5Awrite(a, H5T_NATIVE_INT64, &iv) >= 0
                   : H5Awrite(a, H5T_NATIVE_DOUBLE, &v) >= 0);
  H5Aclose(a);
  H5Fclose(f);
}

/* The restart's clock (issue 39, D2 and D3): time.end before the
 * snapshot's time is refused before any file is touched (restarting in
 * place used to cut diagnostics.csv to the earlier time and leave the
 * later snapshots); a snapshot whose time is NaN, negative or 1e308 (which
 * used to hang the run counting outputs up to it), or whose step is
 * negative, is refused with its file named and nothing written. */
static void test_restart_clock(void) {
  full_run("restart_pc");
  char args[32768], out[65536], dir[4200], a[4300], b[4300];
  snprintf(dir, sizeof dir, "%s/clock", tmp);
  snprintf(args, sizeof args, "rm -rf '%s' && cp -r '%s/restart_pc.full' '%s'", dir, tmp, dir);
  CU_ASSERT_FATAL(sph_test_system(args) == 0);
  snprintf(args, sizeof args, "run -q --restart '%s/snap_0005.h5' -o '%s' --set time.end=0.01", dir,
           dir);
  CU_ASSERT_EQUAL(sph(args, out, sizeof out), 1);
  if (!strstr(out, "is not before time.end = 0.01 s")) printf("\n  %s", out);
  CU_ASSERT(strstr(out, "snap_0005.h5: its time 0.02 s is not before time.end = 0.01 s") != NULL);
  const char *files[] = {"diagnostics.csv", "snapshots.xmf", "snap_0007.h5"};
  for (int i = 0; i < 3; i++) { /* untouched */
    snprintf(a, sizeof a, "%s/restart_pc.full/%s", tmp, files[i]);
    snprintf(b, sizeof b, "%s/%s", dir, files[i]);
    CU_ASSERT_EQUAL(snapcmp_files(a, b), 0);
  }
  /* a restart's closing line counts, and rates, this run's steps (issue
   * 39, D11): the snapshot's step plus this run's is the total */
  snprintf(args, sizeof args, "run --restart '%s/restart_pc.full/snap_0005.h5' -o '%s/clock2'", tmp,
           tmp);
  CU_ASSERT_EQUAL_FATAL(sph_ok(args, out, sizeof out), 0);
  long total = -1, mine = -1;
  const char *end = strstr(out, ": step ");
  CU_ASSERT_FATAL(end != NULL);
  CU_ASSERT(sscanf(end, ": step %ld, %ld steps in this run", &total, &mine) == 2);
  snprintf(a, sizeof a, "%s/restart_pc.full/snap_0005.h5", tmp);
  sph_snapshot *snap;
  sph_error err;
  CU_ASSERT_FATAL(sph_snapshot_open(a, &snap, &err) == 0);
  const long step5 = (long)sph_snapshot_step(snap);
  sph_snapshot_close(snap);
  CU_ASSERT(step5 > 0 && mine > 0 && total == step5 + mine);
  /* hand-edited clocks */
  const struct {
    const char *attr;
    double v;
    int is_int;
    const char *says;
  } bad[] = {{"time", NAN, 0, "its time nan is not a finite time >= 0"},
             {"time", -1.0, 0, "its time -1 is not a finite time >= 0"},
             {"time", 1e308, 0, "is not before time.end"},
             {"step", -5.0, 1, "its step -5"},
             /* a time that cannot follow from its step (issue 61, E13) */
             {"time", -0.0, 0, "its time -0 s does not go with its step"},
             {"time", 1e-320, 0, "its time 9.99989e-321 s does not go with its step"},
             {"time", 0.0, 0, "its time 0 s does not go with its step"}};
  for (int i = 0; i < 7; i++) {
    char edited[4300], outdir[4300];
    snprintf(edited, sizeof edited, "%s/edited%d.h5", tmp, i);
    snprintf(outdir, sizeof outdir, "%s/edited%d.out", tmp, i);
    snprintf(args, sizeof args, "cp '%s/restart_pc.full/snap_0002.h5' '%s'", tmp, edited);
    CU_ASSERT_FATAL(sph_test_system(args) == 0);
    set_attribute(edited, bad[i].attr, bad[i].v, bad[i].is_int);
    snprintf(args, sizeof args, "run -q --restart '%s' -o '%s'", edited, outdir);
    const int st = sph(args, out, sizeof out);
    if (st != 1 || !strstr(out, bad[i].says))
      printf("\n  %s = %g: exit %d: %s", bad[i].attr, bad[i].v, st, out);
    CU_ASSERT_EQUAL(st, 1);
    CU_ASSERT(strstr(out, edited) != NULL && strstr(out, bad[i].says) != NULL);
    FILE *f = fopen(outdir, "r");
    CU_ASSERT(f == NULL); /* nothing written, not even the directory */
    if (f) fclose(f);
  }
  /* a particle's h edited in a constant-h case (issue 61, E13) */
  const double hs[2] = {0.0, 1e6};
  for (int i = 0; i < 2; i++) {
    char edited[4300], outdir[4300];
    snprintf(edited, sizeof edited, "%s/edited_h%d.h5", tmp, i);
    snprintf(outdir, sizeof outdir, "%s/edited_h%d.out", tmp, i);
    snprintf(args, sizeof args, "cp '%s/restart_pc.full/snap_0002.h5' '%s'", tmp, edited);
    CU_ASSERT_FATAL(sph_test_system(args) == 0);
    const hid_t f = H5Fopen(edited, H5F_ACC_RDWR, H5P_DEFAULT);
    CU_ASSERT_FATAL(f >= 0);
    const hid_t d = H5Dopen(f, "particles/h", H5P_DEFAULT);
    CU_ASSERT_FATAL(d >= 0);
    const hid_t space = H5Dget_space(d);
    const hsize_t at = 7, one = 1;
    H5Sselect_hyperslab(space, H5S_SELECT_SET, &at, NULL, &one, NULL);
    const hid_t mem = H5Screate_simple(1, &one, NULL);
    CU_ASSERT(H5Dwrite(d, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, &hs[i]) >= 0);
    H5Sclose(mem);
    H5Sclose(space);
    H5Dclose(d);
    H5Fclose(f);
    snprintf(args, sizeof args, "run -q --restart '%s' -o '%s'", edited, outdir);
    const int st = sph(args, out, sizeof out);
    char says[128];
    snprintf(says, sizeof says, "particle 7 has h = %g m, the case's h is", hs[i]);
    if (st != 1 || !strstr(out, says)) printf("\n  h = %g: exit %d: %s", hs[i], st, out);
    CU_ASSERT_EQUAL(st, 1);
    CU_ASSERT(strstr(out, says) != NULL);
  }
}

int main(void) {
  tmp = sph_test_tmpdir();
  CU_TestInfo tests[] = {
      {"predictor-corrector: restart in a fresh directory is bitwise", test_pc_fresh},
      {"leap-frog: restart in a fresh directory is bitwise", test_lf_fresh},
      {"mirror, periodic: restart in a fresh directory is bitwise", test_mirror_fresh},
      {"leap-frog: restart from t = 0 is bitwise", test_lf_from_start},
      {"free-surface flags on the kept list: restart is bitwise", test_fs_fresh},
      {"adami walls, a moving one, the ledger: restart is bitwise", test_adami_fresh},
      {"the default scheme (leap-frog, changing step): restart is bitwise", test_default_fresh},
      {"a fluid without tension: restart is bitwise", test_no_tension_fresh},
      {"two phases (water under air): restart is bitwise", test_air_fresh},
      {"restart in the run's directory: CSV and XDMF as uninterrupted", test_pc_in_place},
      {"mirror, periodic: restart in place, headers of an earlier version", test_mirror_in_place},
      {"restart in place: CRLF line ends read, rows kept", test_crlf_in_place},
      {"fluid taken out as it leaves: restart is bitwise", test_outflow_fresh},
      {"fluid taken out: restart in place, XDMF counts as uninterrupted", test_outflow_in_place},
      {"restart in place: unreadable rows refused, files left as they were", test_unreadable_rows},
      {"bad restarts fail clearly; time.end may change", test_bad_restarts},
      {"the restart's clock: time.end before it, NaN, negative, 1e308 and step -5 refused",
       test_restart_clock},
      CU_TEST_INFO_NULL};
  int rc = sph_test_main("restart", tests);
  sph_test_rmtree(tmp);
  return rc;
}
