#!/bin/sh
# Regenerates the golden files from the current build. Run it through
# `make golden` (which sets SPH_SRCDIR and SPH_BUILDDIR), look at the diff,
# and commit the new files with a message that says why the numbers moved.
set -eu
src=${SPH_SRCDIR:?run through make golden}
build=${SPH_BUILDDIR:?run through make golden}
sph="$build/src/sph"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sphgolden.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# 1. The coarse Martin & Moyce front (tests/test_dam_break.c).
"$sph" run --quiet --threads 1 "$src/cases/martin_moyce_coarse.yaml" -o "$tmp/mm"
out="$src/golden/martin_moyce_coarse_front.csv"
{
  echo "# golden: surge front of cases/martin_moyce_coarse.yaml at every output time"
  echo "# made by: make golden ($("$sph" --version | head -n 1)); compared within 0.05 dx by tests/test_dam_break.c"
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "time") t = i; if ($i == "front_x") f = i }
                     print "time,front_x"; next }
           { print $t "," $f }' "$tmp/mm/diagnostics.csv"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"

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

