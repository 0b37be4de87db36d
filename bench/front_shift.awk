# SPDX-License-Identifier: BSD-3-Clause
# bench/front_shift.awk - the surge front of a dam-break run against an
# experiment's front, raw and after the best single shift in time: the
# experiment's points are compared with the run at T - s for every lead s
# from -0.6 to +0.6 in steps of 0.005 (T = t sqrt(2 g / a)), and the s with
# the smallest RMS of the relative error of Z = x/a is the run's lead over
# the experiment (positive: the run is ahead). Issue 36 asks for the front
# raw and after the shift, the shift under 0.2: the converged codes all run
# ahead of the experiments' gate.
#
#   awk -F, -v a=A [-v col=K] [-v zmax=Z] -f bench/front_shift.awk RUN.csv EXPERIMENT.csv
#
# RUN.csv: a header line, then rows with the time (s) in column 1 and the
# front x (m) in column K (default 5: diagnostics.csv's front_x).
# EXPERIMENT.csv: comment lines (#), a header line, then T, Z; the points
# with Z < zmax (default 3.9: the front not yet at a 4a tank's far wall)
# and T inside the run's span after the shift are used. Prints
# "RMS_RAW LEAD RMS_SHIFTED" (percent, T, percent).
BEGIN { if (col == "") col = 5; if (zmax == "") zmax = 3.9 }
FILENAME == ARGV[1] { if (FNR > 1) { n++; t[n] = $1 * sqrt(2 * 9.81 / a); z[n] = $col / a }; next }
/^#/ || $1 !~ /^[0-9.+-]/ { next }
$2 < zmax { m++; te[m] = $1; ze[m] = $2 }
function at(tt,   i) {
  if (tt <= t[1]) return z[1]
  for (i = 2; i <= n; i++) if (tt <= t[i]) return z[i-1] + (z[i] - z[i-1]) * (tt - t[i-1]) / (t[i] - t[i-1])
  return -1
}
function rms(s,   k, e, sum, c, v) {
  for (k = 1; k <= m; k++) {
    v = at(te[k] - s); if (v < 0 || te[k] - s < 0) continue
    e = (v - ze[k]) / ze[k]; sum += e * e; c++
  }
  return c >= 3 ? 100 * sqrt(sum / c) : -1
}
END {
  raw = rms(0); best = raw; lead = 0
  for (s = -0.6; s <= 0.6 + 1e-9; s += 0.005) { r = rms(s); if (r >= 0 && r < best) { best = r; lead = s } }
  printf "%.2f %+.3f %.2f\n", raw, lead, best
}
