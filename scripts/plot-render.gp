# Image accuracy vs. frame time of `crowdbake bench render` (docs/performance.md).
# Usage: gnuplot -e "datafile='docs/data/render-bench.dat'; outfile='docs/render-bench.png'; \
#                   sizes='1000 10000 50000'; pop='1000'; device='1280x720, llvmpipe'" \
#                scripts/plot-render.gp
# One panel per crowd size: x = frame time (ms, log), y = PSNR against full resolution (dB;
# full resolution itself sits on the 60 dB line); continuous points are labelled with their
# budget N in thousands of vertices; dashed: the PSNR of both images shrunk 4x (area average). The last panel: the popping measure per frame pair of the
# camera dolly (mean |dLoD - dFull|, 8-bit units; lower = less popping).
# The data file (written by the bench) has one block per size (columns: mode, budget,
# frame_ms, psnr, triangles, psnr_4x) and a last block (columns: pair, then one per sequence).
if (!exists("datafile")) datafile = 'docs/data/render-bench.dat'
if (!exists("outfile")) outfile = 'docs/render-bench.png'
if (!exists("sizes")) sizes = ''
if (!exists("pop")) pop = ''
if (!exists("device")) device = ''
n = words(sizes)
has_pop = (pop ne '' && pop ne '0')
panels = n + (has_pop ? 1 : 0)
cols = (panels <= 2) ? panels : 2
rows = int(ceil(panels / real(cols)))

set terminal pngcairo size 520*cols, 400*rows + 40 font "DejaVu Sans,9"
set output outfile
set multiplot layout rows, cols title "crowdbake render: image accuracy vs. frame time (" . device . ")" font ",10"
set datafile missing NaN
set grid
set key below horizontal font ",8"
is(s) = (strcol(1) eq s)
do for [i = 0:n - 1] {
  set title word(sizes, i + 1) . " instances" noenhanced
  set logscale x
  set format x "%g"
  set xlabel "frame time (ms, lavapipe)"
  set ylabel "PSNR vs. full resolution (dB)"
  set yrange [*:62]
  plot datafile index i using 3:(is('continuous') ? $4 : NaN) with linespoints pt 7 ps 1.1 lc rgb "#1f77b4" title "continuous LoD", \
       '' index i using 3:(is('continuous') ? $6 : NaN) with linespoints pt 6 ps 1.0 dt 2 lc rgb "#1f77b4" title "continuous, PSNR of 4x-shrunk images", \
       '' index i using 3:(is('discrete') ? $6 : NaN) with linespoints pt 4 ps 0.9 dt 2 lc rgb "#d62728" title "discrete, PSNR of 4x-shrunk images", \
       '' index i using 3:(is('discrete') ? $4 : NaN) with linespoints pt 5 ps 1.0 lc rgb "#d62728" title "discrete LoD (4 levels)", \
       '' index i using 3:(is('full') ? $4 : NaN) with points pt 9 ps 1.6 lc rgb "#555555" title "full resolution (reference)", \
       '' index i using 3:4:(is('continuous') ? sprintf("%gk", $2 / 1000) : '') with labels offset char 0.6, char 0.7 font ",7" notitle, \
       35 with lines dt 2 lc rgb "#2ca02c" title "35 dB target"
}
if (has_pop) {
unset logscale x
set title "popping over the camera dolly (" . pop . " instances)" noenhanced
set xlabel "frame pair"
set ylabel "mean |dLoD - dFull| (8-bit units)"
set yrange [0:*]
plot datafile index n using 1:2 with lines lw 2 lc rgb "#1f77b4" title "continuous", \
     '' index n using 1:3 with lines lw 2 lc rgb "#d62728" title "discrete, equal triangles", \
     '' index n using 1:4 with lines lw 1 dt 2 lc rgb "#ff7f0e" title "discrete, same budget"
}
unset multiplot
