# SPDX-License-Identifier: BSD-3-Clause
# bench/spheric2_metrics.awk - a SPHERIC Test 2 run against the measurement.
# usage: awk -F, [-v tmax=2] -f spheric2_metrics.awk EXP.csv RUN/probes.csv
# EXP.csv: tests/data/spheric_test2_kleefsman2005.csv (time,P1..P8,H1..H4 by
# position); probes.csv: a run of cases/spheric_test2.yaml (P1 ... with their
# sensor-model columns P1_low_pass ..., H1-H4). Over t <= tmax (default 2 s,
# or the run's end) prints one line per measure: name, run, experiment, run
# less experiment:
#   arrival_H2  the first time H2 reads more than 2 cm (the surge arrives);
#   drop_H4     the first time H4 reads 2 cm below its start (the reservoir
#               empties: H4 is wet from the start);
#   rise_P1     the first time P1 reads more than 1 kPa (the run's through
#               its sensor model, P1_low_pass);
#   peak_P1, peak_P3  the largest reading (run: the sensor model), and the
#               difference in per cent of the measured peak;
#   rms_H2, rms_H4, rms_P1, rms_P3  the RMS of run less experiment at the
#               experiment's sample times (the run interpolated linearly);
#   arrival_H1, arrival_H3  as arrival_H2, at the other gauges downstream;
#   rise_P3     as rise_P1, at P3;
#   impulse_P1, impulse_P3  the integral of the reading (run: the sensor
#               model) over the first impact, each series over its own
#               window [t_r - 0.035 s, t_r + 0.13 s] about its own rise t_r
#               (Lobovsky's aligned window [T_i - 0.15, T_i + 0.55] in
#               T = t (g/H)^1/2, with H = 0.55 m, the reservoir's depth), in
#               Pa s, and the difference in per cent of the measured one;
#   peak_P5 .. peak_P8  the box top's largest readings, as peak_P1;
#   low_top     the lowest reading of P5-P8 (run: the sensor model), in Pa.
function first_above(t, v, n, name, thr, tmax, i) {
  for (i = 1; i <= n; i++)
    if (t[i] <= tmax && v[name, i] > thr) return t[i]
  return -1
}
function first_below(t, v, n, name, thr, tmax, i) {
  for (i = 1; i <= n; i++)
    if (t[i] <= tmax && v[name, i] < thr) return t[i]
  return -1
}
function peak(t, v, n, name, tmax, i, m) {
  m = -1e30
  for (i = 1; i <= n; i++)
    if (t[i] <= tmax && v[name, i] > m) m = v[name, i]
  return m
}
function at(name, x, lo, hi, mid) { # the run's value at time x, linear between rows
  if (x <= st[1]) return sv[name, 1]
  if (x >= st[ns]) return sv[name, ns]
  lo = 1; hi = ns
  while (hi - lo > 1) { mid = int((lo + hi) / 2); if (st[mid] <= x) lo = mid; else hi = mid }
  return sv[name, lo] + (sv[name, hi] - sv[name, lo]) * (x - st[lo]) / (st[hi] - st[lo])
}
function impulse(t, v, n, name, r, i, s, a, b, lo, hi) { # trapezoids over [r - 0.035, r + 0.13]
  s = 0; lo = r - 0.035; hi = r + 0.13
  for (i = 2; i <= n; i++) {
    a = t[i - 1] < lo ? lo : t[i - 1]; b = t[i] > hi ? hi : t[i]
    if (b <= a) continue
    s += 0.5 * (val_at(t, v, name, i, a) + val_at(t, v, name, i, b)) * (b - a)
  }
  return s
}
function val_at(t, v, name, i, x) { # linear between rows i - 1 and i
  return v[name, i - 1] + (v[name, i] - v[name, i - 1]) * (x - t[i - 1]) / (t[i] - t[i - 1])
}
function low(t, v, n, name, tmax, i, m) {
  m = 1e30
  for (i = 1; i <= n; i++)
    if (t[i] <= tmax && v[name, i] < m) m = v[name, i]
  return m
}
function rms(ename, sname, tmax, i, s, m, d) {
  s = 0; m = 0
  for (i = 1; i <= ne; i++)
    if (et[i] <= tmax) { d = at(sname, et[i]) - ev[ename, i]; s += d * d; m++ }
  return m ? sqrt(s / m) : -1
}
FNR == 1 { file++ }
/^#/ { next }
file == 1 && $1 == "time" { for (k = 1; k <= NF; k++) eh[$k] = k; next }
file == 2 && $1 ~ /^time/ { for (k = 1; k <= NF; k++) { c = $k; sub(/ \(.*/, "", c); sh[c] = k }; next }
file == 1 { ne++; et[ne] = $1; for (q in eh) ev[q, ne] = $(eh[q]); next }
file == 2 { ns++; st[ns] = $1; for (q in sh) sv[q, ns] = $(sh[q]); next }
END {
  if (tmax == "") tmax = 2.0
  if (tmax > st[ns]) tmax = st[ns]
  a = first_above(st, sv, ns, "H2", 0.02, tmax); b = first_above(et, ev, ne, "H2", 0.02, tmax)
  printf "arrival_H2 %.4f %.4f %+.4f\n", a, b, a - b
  a = first_below(st, sv, ns, "H4", sv["H4", 1] - 0.02, tmax)
  b = first_below(et, ev, ne, "H4", ev["H4", 1] - 0.02, tmax)
  printf "drop_H4 %.4f %.4f %+.4f\n", a, b, a - b
  a = first_above(st, sv, ns, "P1_low_pass", 1000, tmax); b = first_above(et, ev, ne, "P1", 1000, tmax)
  printf "rise_P1 %.4f %.4f %+.4f\n", a, b, a - b
  a = peak(st, sv, ns, "P1_low_pass", tmax); b = peak(et, ev, ne, "P1", tmax)
  printf "peak_P1 %.0f %.0f %+.1f\n", a, b, 100 * (a - b) / b
  a = peak(st, sv, ns, "P3_low_pass", tmax); b = peak(et, ev, ne, "P3", tmax)
  printf "peak_P3 %.0f %.0f %+.1f\n", a, b, 100 * (a - b) / b
  printf "rms_H2 %.4f - -\n", rms("H2", "H2", tmax)
  printf "rms_H4 %.4f - -\n", rms("H4", "H4", tmax)
  printf "rms_P1 %.0f - -\n", rms("P1", "P1_low_pass", tmax)
  printf "rms_P3 %.0f - -\n", rms("P3", "P3_low_pass", tmax)
  printf "until %.3f - -\n", tmax
  for (k = 1; k <= 3; k += 2) {
    a = first_above(st, sv, ns, "H" k, 0.02, tmax); b = first_above(et, ev, ne, "H" k, 0.02, tmax)
    printf "arrival_H%d %.4f %.4f %+.4f\n", k, a, b, a - b
  }
  a = first_above(st, sv, ns, "P3_low_pass", 1000, tmax); b = first_above(et, ev, ne, "P3", 1000, tmax)
  printf "rise_P3 %.4f %.4f %+.4f\n", a, b, a - b
  for (k = 1; k <= 3; k += 2) {
    ra = first_above(st, sv, ns, "P" k "_low_pass", 1000, tmax); rb = first_above(et, ev, ne, "P" k, 1000, tmax)
    a = ra > 0 ? impulse(st, sv, ns, "P" k "_low_pass", ra) : 0
    if (rb > 0) { b = impulse(et, ev, ne, "P" k, rb); printf "impulse_P%d %.1f %.1f %+.1f\n", k, a, b, 100 * (a - b) / b }
    else printf "impulse_P%d %.1f - -\n", k, a # (the measurement has not risen by tmax)
  }
  lt = 1e30; le = 1e30
  for (k = 5; k <= 8; k++) {
    a = peak(st, sv, ns, "P" k "_low_pass", tmax); b = peak(et, ev, ne, "P" k, tmax)
    printf "peak_P%d %.0f %.0f %+.1f\n", k, a, b, 100 * (a - b) / b
    a = low(st, sv, ns, "P" k "_low_pass", tmax); if (a < lt) lt = a
    b = low(et, ev, ne, "P" k, tmax); if (b < le) le = b
  }
  printf "low_top %.0f %.0f %+.0f\n", lt, le, lt - le
}
