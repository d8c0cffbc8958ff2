# Image accuracy vs. frame time of `crowdbake bench render` (docs/performance.md).
# Usage: gnuplot -e "datafile='docs/data/render-bench.dat'; popfile='docs/data/render-popping.dat'; \
#                   outfile='docs/render-bench.png'; sizes='1000 10000 50000'; device='...'" \
#                scripts/plot-render.gp
# One panel per crowd size: x = frame time (ms, log), y = PSNR against full resolution (dB;
# full resolution itself sits on the 60 dB line); continuous points are labelled with their
# budget N in thousands of vertices (not those tuned to a discrete row's triangles, whose N is
# not a round number); dashed: the PSNR of both images shrunk 4x (area average).
# The last panel (when popfile is given): the popping measure per frame pair of the camera
# dolly, continuous vs. discrete at an equal triangle count — the share of 4x-shrunk pixels
# whose change differs from full resolution's by more than 24 (visible pops), and the mean
# change |dLoD - dFull| on 4x-shrunk images (lower = less popping).
# datafile: one block per size (columns: mode, budget, frame_ms, psnr, triangles, psnr_4x);
# popfile: pair, then per sequence (continuous, discrete equal, discrete same budget, full,
# continuous with geomorphs, error-driven at equal triangles) three columns: change_4x, error
# jump, popping pixels (%).
if (!exists("datafile")) datafile = 'docs/data/render-bench.dat'
if (!exists("popfile")) popfile = ''
if (!exists("outfile")) outfile = 'docs/render-bench.png'
if (!exists("sizes")) sizes = ''
if (!exists("device")) device = ''
n = words(sizes)
has_pop = (popfile ne '')
panels = n + (has_pop ? 1 : 0)
cols = (panels <= 2) ? panels : 2
rows = int(ceil(panels / real(cols)))

set terminal pngcairo size 560*cols, 420*rows + 40 font "DejaVu Sans,9"
set output outfile
set multiplot layout rows, cols title "crowdbake render: image accuracy vs. frame time (" . device . ")" font ",10"
set datafile missing NaN
set grid
set key below horizontal font ",8" maxrows 3
is(s) = (strcol(1) eq s)
do for [i = 0:n - 1] {
  set title word(sizes, i + 1) . " instances" noenhanced
  set logscale x
  set format x "%g"
  set xlabel "frame time (ms, lavapipe)"
  set ylabel "PSNR vs. full resolution (dB)"
  set yrange [10:62]
  plot datafile index i using 3:(is('continuous') ? $4 : NaN) with linespoints pt 7 ps 1.1 lc rgb "#1f77b4" title "continuous LoD", \
       '' index i using 3:(is('discrete') ? $4 : NaN) with linespoints pt 5 ps 1.0 lc rgb "#d62728" title "discrete LoD (4 levels)", \
       '' index i using 3:(is('continuous') ? $6 : NaN) with linespoints pt 6 ps 1.0 dt 2 lc rgb "#1f77b4" title "continuous, 4x-shrunk images", \
       '' index i using 3:(is('discrete') ? $6 : NaN) with linespoints pt 4 ps 0.9 dt 2 lc rgb "#d62728" title "discrete, 4x-shrunk images", \
       '' index i using 3:(is('error') ? $4 : NaN) with linespoints pt 13 ps 1.3 lc rgb "#2ca02c" title "error-driven (0.5, 1, 2 px)", \
       '' index i using 3:(is('error') ? $6 : NaN) with linespoints pt 12 ps 1.1 dt 2 lc rgb "#2ca02c" title "error-driven, 4x-shrunk images", \
       '' index i using 3:(is('uniform') ? $4 : NaN) with linespoints pt 8 ps 1.1 dt 4 lc rgb "#8c564b" title "one level for every instance (--uniform-levels)", \
       '' index i using 3:(is('full') ? $4 : NaN) with points pt 9 ps 1.6 lc rgb "#555555" title "full resolution (reference)", \
       '' index i using 3:4:(is('continuous') && int($2) % 1000 == 0 ? sprintf("%gk", $2 / 1000) : '') with labels offset char 0.6, char 0.7 font ",7" notitle, \
       35 with lines dt 3 lc rgb "#2ca02c" title "35 dB target"
}
if (has_pop) {
  unset logscale x
  set title "popping over the camera dolly (animation frozen), equal triangles" noenhanced
  set xlabel "frame pair"
  set ylabel "popping pixels (% of 4x-shrunk pixels)"
  set y2label "mean |dLoD - dFull|, 4x-shrunk (8-bit units)"
  set ytics nomirror
  set y2tics
  set yrange [0:*]
  set y2range [0:*]
  plot popfile using 1:4 with lines lw 2 lc rgb "#1f77b4" title "continuous (budget): popping pixels", \
       '' using 1:19 with lines lw 2 lc rgb "#2ca02c" title "error-driven: popping pixels", \
       '' using 1:7 with lines lw 2 lc rgb "#d62728" title "discrete: popping pixels", \
       '' using 1:16 with lines lw 1 lc rgb "#9467bd" title "continuous with geomorphs: popping pixels", \
       '' using 1:2 axes x1y2 with lines lw 1 dt 2 lc rgb "#1f77b4" title "continuous: mean change (right)", \
       '' using 1:5 axes x1y2 with lines lw 1 dt 2 lc rgb "#d62728" title "discrete: mean change (right)"
}
unset multiplot
