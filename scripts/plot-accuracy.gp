# Accuracy vs. time plot of `crowdbake bench simplify` (docs/accuracy.md).
# Usage: gnuplot -e "datafile='docs/data/accuracy-vs-time.dat'; outfile='docs/accuracy-vs-time.png'; \
#                   assets='spectator Fox ...'" scripts/plot-accuracy.gp
# One panel per asset: x = simplification wall time (s, log), y = animated mean-RMS error at
# 25% kept positions (% of the bind-pose diagonal); DQEM points are labelled with S.
# The bench passes the variables; the data file has one block per asset (columns: label,
# series, seconds, rms25, max25, rms10).
if (!exists("datafile")) datafile = 'docs/data/accuracy-vs-time.dat'
if (!exists("outfile")) outfile = 'docs/accuracy-vs-time.png'
if (!exists("assets")) assets = ''
stats datafile using 3 nooutput
n = STATS_blocks
cols = (n <= 1) ? 1 : (n <= 4 ? 2 : 3)
rows = int(ceil(n / real(cols)))

set terminal pngcairo size 440*cols, 380*rows + 40 font "DejaVu Sans,9"
set output outfile
set multiplot layout rows, cols title "Mean-RMS animated error at 25% kept vs. time (lower left is better)" font ",10"
set logscale x
set format x "%g"
set xlabel "simplification time (s)"
set ylabel "mean-RMS error (% of diagonal)"
set key below horizontal maxrows 2 font ",7" samplen 1 width -2
set grid
set yrange [0:*]
set datafile missing NaN

is(s) = (strcol(2) eq s)
do for [i = 0:n - 1] {
  set title (words(assets) > i ? word(assets, i + 1) : sprintf("asset %d", i + 1)) noenhanced
  plot datafile index i using 3:(is('static') ? $4 : NaN) with points pt 9 ps 1.4 lc rgb "#555555" title "S=1 static QEM", \
       '' index i using 3:(is('pullback') ? $4 : NaN) with points pt 7 ps 1.1 lc rgb "#1f77b4" title "DQEM pullback", \
       '' index i using 3:(is('exact') ? $4 : NaN) with points pt 5 ps 1.1 lc rgb "#d62728" title "DQEM exact", \
       '' index i using 3:(is('clips') ? $4 : NaN) with points pt 13 ps 1.3 lc rgb "#2ca02c" title "DQEM clip poses", \
       '' index i using 3:(is('meshopt') ? $4 : NaN) with points pt 2 ps 1.6 lc rgb "#ff7f0e" title "meshoptimizer 0.18", \
       '' index i using 3:(is('gltfpack') ? $4 : NaN) with points pt 3 ps 1.6 lc rgb "#9467bd" title "gltfpack", \
       '' index i using 3:($4):(strcol(1) eq '-' ? '' : strcol(1)) with labels offset char 0.9, char 0.5 font ",7" notitle
}
unset multiplot
