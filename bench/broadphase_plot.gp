# Log-log plot of bench_broadphase's CSV: ms per step against bodies, one line per broad phase
# with its fitted slope, rain and pile side by side. Usage (gnuplot from Debian's gnuplot-nox):
#   gnuplot -e "csv='bench-out/broadphase_bench.csv'; out='docs/img/broadphase.png'" bench/broadphase_plot.gp
if (!exists("csv")) csv = 'bench-out/broadphase_bench.csv'
if (!exists("out")) out = 'docs/img/broadphase.png'

set terminal pngcairo size 1200,520 font ",10" noenhanced
set output out
set datafile separator ','
set logscale xy
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key top left
set xlabel 'bodies'
set ylabel 'broad phase, ms per step (median)'
set xrange [700:90000]
set xtics (1000, 4000, 16000, 64000)
set fit quiet
set fit logfile '/dev/null'

choices = 'auto all_pairs sweep_and_prune uniform_grid quadtree aabb_tree'
# auto dashed and wide, drawn under the structure it picks.
set linetype 1 lc rgb '#444444' lw 5 dt 2 pt 6 ps 1.4
set linetype 2 lc rgb '#9400d3' lw 2 pt 7 ps 0.8
set linetype 3 lc rgb '#009e73' lw 2 pt 7 ps 0.8
set linetype 4 lc rgb '#56b4e9' lw 2 pt 7 ps 0.8
set linetype 5 lc rgb '#e69f00' lw 2 pt 7 ps 0.8
set linetype 6 lc rgb '#d55e00' lw 2 pt 7 ps 0.8
# The rows of one scene and one broad phase, in file order (n ascending).
rows(scene, choice) = sprintf("< awk -F, '$1 == \"%s\" && $2 == \"%s\"' %s", scene, choice, csv)

set multiplot layout 1,2
do for [scene in 'rain pile'] {
  set title scene eq 'rain' ? 'even rain (spread thin, falling)' : 'clumped pile (packed, jiggling)'
  titles = ''
  do for [c in choices] {
    a = 1
    b = -5
    # The least-squares slope of log(ms) against log(n), as the benchmark prints it.
    fit [*:*] a * x + b rows(scene, c) using (log($3)):(log($4)) via a, b
    titles = titles . sprintf('%s (slope %.2f)|', c, a)
  }
  plot for [k = 1:words(choices)] rows(scene, word(choices, k)) using 3:4 with linespoints lt k \
       title system(sprintf("echo '%s' | cut -d'|' -f%d", titles, k))
}
unset multiplot
