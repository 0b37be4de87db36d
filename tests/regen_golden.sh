#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates the golden files from the current build. Run it through
# `make golden` (which sets SPH_SRCDIR and SPH_BUILDDIR), look at the diff,
# and commit the new files with a message that says why the numbers moved.
set -eu
src=${SPH_SRCDIR:?run through make golden}
build=${SPH_BUILDDIR:?run through make golden}
sph="$build/src/sph"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sphgolden.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# The surge front (time, front_x) of a run's diagnostics.csv as a golden
# file: front_golden RUN_DIR CASE_NAME TEST OUT
front_golden() {
  {
    echo "# golden: surge front of cases/$2.yaml at every output time"
    echo "# made by: make golden ($("$sph" --version | head -n 1)); compared within 0.05 dx by tests/$3.c"
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { n = $i; sub(/ \(.*\)$/, "", n)  # "time (s)": time
                         if (n == "time") t = i; if (n == "front_x") f = i }
                       print "time,front_x"; next }
             { print $t "," $f }' "$1/diagnostics.csv"
  } > "$4.tmp"
  mv "$4.tmp" "$4"
  echo "wrote $4"
}

# 1. The coarse Martin & Moyce front (tests/test_dam_break.c).
"$sph" run --quiet --threads 1 "$src/cases/martin_moyce_coarse.yaml" -o "$tmp/mm"
front_golden "$tmp/mm" martin_moyce_coarse test_dam_break "$src/golden/martin_moyce_coarse_front.csv"

# 2. The energy audit of the wet-bed dam break at CI-sized counts
#    (tests/test_energy.c).
"$sph" audit --quiet "$src/cases/wet_bed_dam_break.yaml" --particles 500,1000,2000 \
  --times 0.156,0.281,0.343,0.406,0.468,0.531 -o "$tmp/audit" > /dev/null
out="$src/golden/energy_drift.csv"
{
  echo "# golden: sph audit cases/wet_bed_dam_break.yaml --particles 500,1000,2000 (closed energy balance)"
  echo "# made by: make golden ($("$sph" --version | head -n 1)); compared within 1e-5 + 5 % by tests/test_energy.c"
  cat "$tmp/audit/audit.csv"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"

# 3. Free-surface flags of the coarse dam break at t = 0.1 s
# (tests/test_freesurface_run.c): the test program itself runs `sph` with
# one thread and writes golden/freesurface/dam_break_coarse_t0.1.csv, so the
# extraction and the comparison share one reader. It is a check program,
# not built by `make all`: build it first.
${MAKE:-make} -s -C "$build" tests/test_freesurface_run
SPH_SRCDIR="$src" SPH_BUILDDIR="$build" "$build/tests/test_freesurface_run" --regen

# 4. The coarse SPS dam-break front (tests/test_turbulence.c).
"$sph" run --quiet "$src/cases/sps_dam_break_coarse.yaml" -o "$tmp/sps" --set output.snapshots=false
front_golden "$tmp/sps" sps_dam_break_coarse test_turbulence "$src/golden/sps_dam_break_coarse_front.csv"

# 5. The coarse wave-gauge record of the flap wavemaker (tests/test_waves.c).
"$sph" run --quiet "$src/cases/linear_wave_coarse.yaml" -o "$tmp/wave"
out="$src/golden/linear_wave_coarse_gauge.csv"
{
  echo "# golden: gauges.csv of cases/linear_wave_coarse.yaml (surface elevation at x = 27.3 m)"
  echo "# made by: make golden ($("$sph" --version | head -n 1)); compared within 0.02 m by tests/test_waves.c"
  cat "$tmp/wave/gauges.csv"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"

# 6. The inclined-plane table on a CI-sized subset (tests/test_inclined_sweep.c):
#    bench/inclined_plane with fixed_layers at 100, 400, 900, 1600 and repulsive at
#    100, 400 fluid particles.
SPH="$sph" OUT="$tmp/ipa" CONFIGS=fixed_layers COUNTS="100 400 900 1600" sh "$src/bench/inclined_plane" > /dev/null
SPH="$sph" OUT="$tmp/ipb" CONFIGS=repulsive COUNTS="100 400" sh "$src/bench/inclined_plane" > /dev/null
out="$src/golden/inclined_plane_ci.csv"
{
  echo "# golden: bench/inclined_plane, fixed_layers at 100/400/900/1600 and repulsive at 100/400 fluid particles"
  echo "# (film flow at t = 4 s against paper A eq. 26, max and L2 in % of v_max; wall_s, a timing, is written as 0)"
  echo "# made by: make golden ($("$sph" --version | head -n 1)); compared within 1 % + 0.005 by tests/test_inclined_sweep.c"
  { cat "$tmp/ipa/inclined_plane.csv"; tail -n +2 "$tmp/ipb/inclined_plane.csv"; } |
    awk -F, -v OFS=, 'NR > 1 { $7 = 0 } { print }'
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
