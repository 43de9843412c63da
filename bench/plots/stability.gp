# Stability against cost: each stress scene's stability figure against ms/step for ballbox's
# solver settings (bench_solver's CSV; confined circles from bench_peers' sweep) with Box2D 2.4 and
# Chipmunk 7 beside them (bench_peers' CSV, same figure from body states). Usage (gnuplot-nox):
#   gnuplot -e "dir='bench-out'; img='docs/img'" bench/plots/stability.gp
if (!exists("dir")) dir = 'bench-out'
if (!exists("img")) img = 'docs/img'
# Scene names hold commas inside quotes, which gnuplot's CSV reading would split: read each CSV
# through awk as tab-separated fields with the quotes dropped.
tsv(f) = "< awk '{o = \"\"; q = 0; n = length($0); for (i = 1; i <= n; i++) {c = substr($0, i, 1); if (c == \"\\\"\") {q = !q; continue}; if (c == \",\" && !q) c = \"\\t\"; o = o c}; print o}' ".f
set datafile separator "\t"
solver = tsv(dir.'/solver_bench.csv')
peers = tsv(dir.'/peers_bench.csv')

set terminal pngcairo size 1500,1350 font ",9"
set output img.'/stability.png'
set logscale xy
set format y '10^{%L}'
set grid xtics ytics lc rgb '#dddddd'
set key below horizontal font ",8"
set xlabel 'ms/step (median)'
set format x '%g'
floor = 1e-6
if (!exists("ifirst")) ifirst = 1
# A figure of exactly 0 (nothing moved) has no logarithm: it is drawn at the floor.
lift(v) = v < floor ? floor : v

scenes = '"pyramid base 20" "pyramid base 40" "stack of 20" "heavy on light 1000:1" "overlap recovery (base 4, 25%)" "pour 4000 circles r 0.25" "bouncing ball e 0.8 from 10 m" "Newton''s cradle, 5 + striker" "confined 625 circles"'
figures = '"max drift" "max drift" "max drift" "heavy box sank" "overlap left" "max overlap" "max apex error" "others'' max speed" "peak / start kinetic energy"'
units = '"m" "m" "m" "m" "m" "m" "relative" "m/s" "ratio"'

# solver_bench.csv: figure in column 9, value in 10 (after the CPU time); peers_bench.csv: 8 and 9.
ballbox(s, f, v) = (strcol(1) eq s && strcol(9) eq f) ? v : NaN
# The sequential-impulse solver is "sequential_impulse" in both CSVs (before the engine renamed it: "seed").
impulse(name) = name eq 'sequential_impulse' || name eq 'seed'
label(s, f) = (strcol(1) eq s && strcol(9) eq f) ? (impulse(strcol(2)) ? 'seq. impulse' : strcol(3)) : ''
sweep(s, f, v) = (strcol(1) eq s && strcol(8) eq f && strcol(2)[1:8] eq 'ballbox ') ? v : NaN
sweeplabel(s, f) = (strcol(1) eq s && strcol(8) eq f && strcol(2)[1:8] eq 'ballbox ') ? (impulse(strcol(2)[9:]) ? 'seq. impulse' : strcol(2)[9:]) : ''
peer(s, f, e, v) = (strcol(1) eq s && strcol(8) eq f && strcol(2) eq e) ? v : NaN

set multiplot layout 3,3 title "Stability against cost, 60 Hz, sleeping off (ballbox: sequential impulse, then substeps 1 2 4 8; a figure of 0 is drawn at 1e-6)" font ",11"
do for [i = ifirst:9] {
  s = word(scenes, i)
  f = word(figures, i)
  set title sprintf('%s: %s', s, f)
  set ylabel sprintf('%s, %s', f, word(units, i))
  if (i < 9) {
    plot solver skip 1 using (ballbox(s, f, $6)):(lift(ballbox(s, f, $10))) with points pt 7 ps 1.3 lc rgb '#1f77b4' title 'ballbox (bench\_solver)', \
         solver skip 1 using (ballbox(s, f, $6)):(lift(ballbox(s, f, $10))):(label(s, f)) with labels offset 0.8,0.8 font ",8" notitle, \
         peers skip 1 using (peer(s, f, 'Box2D 2.4.1', $6)):(lift(peer(s, f, 'Box2D 2.4.1', $9))) with points pt 5 ps 1.6 lc rgb '#d62728' title 'Box2D 2.4.1', \
         peers skip 1 using (peer(s, f, 'Chipmunk 7.0.3', $6)):(lift(peer(s, f, 'Chipmunk 7.0.3', $9))) with points pt 9 ps 1.8 lc rgb '#2ca02c' title 'Chipmunk 7.0.3'
  } else {
    plot peers skip 1 using (sweep(s, f, $6)):(lift(sweep(s, f, $9))) with points pt 7 ps 1.3 lc rgb '#1f77b4' title 'ballbox (bench\_peers)', \
         peers skip 1 using (sweep(s, f, $6)):(lift(sweep(s, f, $9))):(sweeplabel(s, f)) with labels offset 0.8,0.8 font ",8" notitle, \
         peers skip 1 using (peer(s, f, 'Box2D 2.4.1', $6)):(lift(peer(s, f, 'Box2D 2.4.1', $9))) with points pt 5 ps 1.6 lc rgb '#d62728' title 'Box2D 2.4.1', \
         peers skip 1 using (peer(s, f, 'Chipmunk 7.0.3', $6)):(lift(peer(s, f, 'Chipmunk 7.0.3', $9))) with points pt 9 ps 1.8 lc rgb '#2ca02c' title 'Chipmunk 7.0.3'
  }
}
unset multiplot
