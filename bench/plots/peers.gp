# Each peer's ms/step and headline figure divided by ballbox's, per scene (bench_peers'
# peers_ratios.csv), log scale: above 1 the peer is slower, or less accurate. Usage (gnuplot-nox):
#   gnuplot -e "dir='bench-out'; img='docs/img'" bench/plots/peers.gp
if (!exists("dir")) dir = 'bench-out'
if (!exists("img")) img = 'docs/img'
# Scene names hold commas inside quotes, which gnuplot's CSV reading would split: read each CSV
# through awk as tab-separated fields with the quotes dropped.
tsv(f) = "< awk '{o = \"\"; q = 0; n = length($0); for (i = 1; i <= n; i++) {c = substr($0, i, 1); if (c == \"\\\"\") {q = !q; continue}; if (c == \",\" && !q) c = \"\\t\"; o = o c}; print o}' ".f
set datafile separator "\t"
csv = tsv(dir.'/peers_ratios.csv')

set terminal pngcairo size 1500,1000 font ",9"
set output img.'/peers.png'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set logscale y
set format y '10^{%L}'
set grid ytics lc rgb '#dddddd'
set xtics rotate by -30 left font ",8"
set key top left box opaque
# A ratio against a ballbox figure of 0 is infinite: drawn at the top of the axis.
cap(v) = v != v ? NaN : (v > 1e4 ? 1e4 : (v < 1e-3 ? 1e-3 : v))

set multiplot layout 2,1
set yrange [0.05:50]
set title 'Run time per step, peer ÷ ballbox (above 1: ballbox is faster)'
plot csv skip 1 using (cap($2)):xtic(1) lc rgb '#d62728' title 'Box2D 2.4.1', \
     '' skip 1 using (cap($3)) lc rgb '#2ca02c' title 'Chipmunk 7.0.3', 1 lc rgb 'black' lw 1.5 notitle
set yrange [1e-3:1e4]
set title "Each scene's headline figure (table below), peer ÷ ballbox (above 1: ballbox is more accurate; ballbox's 0 drawn at 10^4)"
plot csv skip 1 using (cap($4)):xtic(1) lc rgb '#d62728' title 'Box2D 2.4.1', \
     '' skip 1 using (cap($5)) lc rgb '#2ca02c' title 'Chipmunk 7.0.3', 1 lc rgb 'black' lw 1.5 notitle
unset multiplot
