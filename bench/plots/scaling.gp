# Scaling: ms/step against bodies, log-log, one line per engine with its fitted slope, circle pour
# and box pile side by side (bench_scaling's CSV). Usage (gnuplot-nox):
#   gnuplot -e "dir='bench-out'; img='docs/img'" bench/plots/scaling.gp
if (!exists("dir")) dir = 'bench-out'
if (!exists("img")) img = 'docs/img'
# Scene names hold commas inside quotes, which gnuplot's CSV reading would split: read each CSV
# through awk as tab-separated fields with the quotes dropped.
tsv(f) = "< awk '{o = \"\"; q = 0; n = length($0); for (i = 1; i <= n; i++) {c = substr($0, i, 1); if (c == \"\\\"\") {q = !q; continue}; if (c == \",\" && !q) c = \"\\t\"; o = o c}; print o}' ".f
set datafile separator "\t"
csv = tsv(dir.'/scaling.csv')
slopes = dir.'/scaling_slopes.csv'

set terminal pngcairo size 1400,560 font ",10"
set output img.'/scaling.png'
set logscale xy
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key top left box opaque
set xlabel 'bodies'
set ylabel 'ms per step (median)'
set xrange [700:90000]
set xtics (1000, 2000, 4000, 8000, 16000, 32000, 64000)

engines = '"ballbox" "Box2D 2.4.1" "Chipmunk 7.0.3"'
colors = '#1f77b4 #d62728 #2ca02c'
slope(s, e) = system(sprintf("awk -F, -v s='%s' -v e='%s' '{gsub(/\"/, \"\")} $1 == s && $2 == e {printf \"%%.2f\", $3}' %s", s, e, slopes))
# One engine's rows of one scene (the CSV interleaves engines within a size), so lines join them.
series(s, e) = sprintf("%s | awk -F'\\t' -v s='%s' -v e='%s' '$1 == s && $3 == e'", csv, s, e)

set multiplot layout 1,2
do for [s in '"circle pour" "box pile"'] {
  set title sprintf('%s: %s, nothing turns, whole-world step', s, s eq 'box pile' ? 'boxes of 0.5 m' : 'circles of radius 0.25 m')
  plot for [i = 1:3] series(s, word(engines, i)) using 2:6 with linespoints lw 2 pt 7 ps 0.9 lc rgb word(colors, i) \
       title (slope(s, word(engines, i)) eq '' ? word(engines, i) : sprintf('%s (slope %s)', word(engines, i), slope(s, word(engines, i))))
}
unset multiplot
