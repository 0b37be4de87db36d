# SPDX-License-Identifier: BSD-3-Clause
# bench/front_error.awk - the surge front of a dam-break run against an
# experiment's front (Martin & Moyce 1952, Koshizuka & Oka 1996): the
# relative error of Z = x/a at each measured T = t sqrt(2 g / a) with
# Z < zmax (default 3.9: the front not yet at a 4a tank's far wall), the
# run's front interpolated linearly in time (after its last row: its last
# value). Used by bench/run, bench/pareto, bench/peers and bench/validation.
#
#   awk -F, -v a=A [-v col=K] [-v x0=X] [-v fmt=F] [-v zmax=Z] [-v lead=1] \
#       -f bench/front_error.awk RUN.csv EXPERIMENT.csv
#
# RUN.csv: a header line, then rows with the time (s) in column 1 and the
# front x (m) in column K (default 2; diagnostics.csv: 5); X (default 0) is
# subtracted from x first (the left wall face's x). EXPERIMENT.csv: comment
# lines, a header line, then T, Z. Prints the RMS and the largest error in
# percent through printf format F (default "%.2f,%.2f"; "nan,nan" when no
# experimental point is used).
# lead=1 (issue 36: the front raw and after the best single shift in time):
# the experiment's points are compared with the run at T - s for every lead
# s from -0.6 to +0.6 in steps of 0.005, only the points whose T - s lies
# inside the run (at least 3), and the s with the smallest RMS is the run's
# lead over the experiment (positive: the run is ahead). Prints
# "RMS_RAW LEAD RMS_SHIFTED" (percent, T, percent) instead.
BEGIN { if (col == "") col = 2; if (fmt == "") fmt = "%.2f,%.2f"; if (zmax == "") zmax = 3.9 }
FNR == 1 { next }
FILENAME == ARGV[1] { n++; t[n] = $1; x[n] = $col - x0; next }
$1 !~ /^[0-9.+-]/ { next }
$2 < zmax { m++; te[m] = $1; ze[m] = $2 }
# the run's Z at the experiment's T - s; with lead=1, -1 outside the run
function z_at(T,   tt, i) {
  tt = T / sqrt(2 * 9.81 / a)
  if (lead && (tt < t[1] || tt > t[n])) return -1
  for (i = 2; i <= n; i++) if (tt <= t[i]) return (x[i-1] + (x[i] - x[i-1]) * (tt - t[i-1]) / (t[i] - t[i-1])) / a
  return x[n] / a
}
# the RMS error in percent with the lead s (-1: too few points); sets mx
function rms(s,   k, v, e, sum, c) {
  mx = 0
  for (k = 1; k <= m; k++) {
    v = z_at(te[k] - s); if (v < 0) continue
    e = (v - ze[k]) / ze[k]; sum += e * e; c++; if (e < 0) e = -e; if (e > mx) mx = e
  }
  return c >= (lead ? 3 : 1) ? 100 * sqrt(sum / c) : -1
}
END {
  raw = rms(0)
  if (!lead) { if (raw < 0) printf "nan,nan"; else printf fmt, raw, 100 * mx; exit }
  best = raw; s0 = 0
  for (s = -0.6; s <= 0.6 + 1e-9; s += 0.005) { r = rms(s); if (r >= 0 && r < best) { best = r; s0 = s } }
  printf "%.2f %+.3f %.2f\n", raw, s0, best
}
