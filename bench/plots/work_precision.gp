# Work-precision diagrams from bench_work_precision's CSV: one PNG per scenario, x = error,
# y = run time per simulated second, log-log, one line per integrator (a marker per h), unstable
# runs circled and labelled, the fitted order in each legend entry. Usage (gnuplot-nox):
#   gnuplot -e "dir='bench-out'; img='docs/img'" bench/plots/work_precision.gp
if (!exists("dir")) dir = 'bench-out'
if (!exists("img")) img = 'docs/img'
csv = dir.'/work_precision.csv'
orders = dir.'/work_precision_orders.csv'

set terminal pngcairo size 800,600 font ",10"
set datafile separator ','
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid xtics ytics lc rgb '#dddddd'
set key bottom left box opaque font ",9" spacing 1.1
set ylabel 'run time per simulated second, µs (median)'
set autoscale x

methods = '"semi-implicit Euler" "explicit Euler" "velocity Verlet" "midpoint" "RK4"'
colors = '#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e'
titles = 'S1 projectile|S2 undamped spring|S3 damped spring|S4 linear drag|S5 quadratic drag|S6 Kepler orbit e = 0.6|S7 bouncing ball e = 0.8'

# The fitted order of a method from the orders CSV (quotes stripped; names hold no commas).
order(s, m, energy) = system(sprintf("awk -F, -v s='%s' -v m='%s' -v e=%d '{gsub(/\"/, \"\")} $1 == s && $3 == m {print (e ? ($8 != \"\" ? $8 : sprintf(\"%%.2f\", $7)) : ($6 != \"\" ? $6 : sprintf(\"%%.2f\", $5)))}' %s", s, m, energy, orders))
# Rows of one scenario and method; the others become NaN, which gnuplot skips. Non-finite
# errors (a blow-up) are drawn at the right edge so they stay visible.
edge(x) = (x != x || x > 1e3) ? 1e3 : (x < 1e-15 ? 1e-15 : x)
pick(s, m, v) = (strcol(1) eq s && strcol(2) eq m) ? v : NaN
unstable(s, v) = (strcol(1) eq s && column(13) == 1) ? v : NaN
first(s, v) = (strcol(1) eq s && column(16) == 1) ? v : NaN

do for [k = 1:7] {
  s = sprintf('S%d', k)
  name = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, k))
  conservative = (s eq 'S2' || s eq 'S6')
  set output sprintf('%s/work_precision_%s.png', img, s)
  if (conservative) { set terminal pngcairo size 1600,600 font ",10"; set multiplot layout 1,2 }
  do for [panel = 0:conservative] {
    col = panel ? 11 : 10
    set xlabel panel ? 'max relative energy error over the run' : 'max position error over the run, m'
    set title sprintf('%s: %s against run time (markers: h = 1/30 .. 1/3840 s)', name, panel ? 'energy error' : 'error')
    plot for [i = 1:5] csv skip 1 using (edge(pick(s, word(methods, i), column(col)))):(pick(s, word(methods, i), $8)) \
           with linespoints lw 2 pt 7 ps 0.9 lc rgb word(colors, i) \
           title sprintf('%s (order %s)', word(methods, i), order(s, word(methods, i), panel)), \
         csv skip 1 using (edge(unstable(s, column(col)))):(unstable(s, $8)) \
           with points pt 6 ps 2.2 lw 1.5 lc rgb 'black' title 'unstable run', \
         csv skip 1 using (edge(first(s, column(col)))):(first(s, $8)):('unstable') \
           with labels offset 0,1.2 font ",9" notitle
  }
  if (conservative) { unset multiplot; set terminal pngcairo size 800,600 font ",10" }
}
