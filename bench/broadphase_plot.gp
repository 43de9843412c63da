# Log-log plot of bench_broadphase's CSV: ms per step against bodies, one line per broad phase,
# rain and pile side by side. Usage (gnuplot from Debian's gnuplot-nox):
#   gnuplot -e "csv='bench-out/broadphase_bench.csv'; out='docs/img/broadphase.png'" bench/broadphase_plot.gp
if (!exists("csv")) csv = 'bench-out/broadphase_bench.csv'
if (!exists("out")) out = 'docs/img/broadphase.png'

set terminal pngcairo size 1200,520 font ",10"
set output out
set datafile separator ','
set logscale xy
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key top left
set xlabel 'bodies'
set ylabel 'broad phase, ms per step (median)'
set xrange [700:90000]
set xtics (1000, 4000, 16000, 64000)

choices = 'all_pairs sweep_and_prune uniform_grid quadtree aabb_tree'
# Rows of one scene and one broad phase: the others become NaN, which gnuplot skips.
pick(scene, choice, column) = (strcol(1) eq scene && strcol(2) eq choice) ? column : NaN

set multiplot layout 1,2
do for [scene in 'rain pile'] {
  set title scene eq 'rain' ? 'even rain (spread thin, falling)' : 'clumped pile (packed, jiggling)'
  plot for [c in choices] csv skip 1 using (pick(scene, c, $3)):(pick(scene, c, $4)) \
       with linespoints lw 2 pt 7 ps 0.8 title c
}
unset multiplot
