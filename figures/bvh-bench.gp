# The plot of figures/bvh-bench.png: BVH build time and tracing throughput
# against the number of triangles, from the table that tools/bench_table.py
# makes of figures/data/bvhbench-levels.json. Run by make figures:
#   gnuplot -e "datafile='TABLE'" -e "outfile='figures/bvh-bench.png'" figures/bvh-bench.gp
# Columns: 1 triangles; first version (BVHAccel): 2 build ms, 3 camera Mrays/s,
# 4 incoherent Mrays/s; final version (FastBVHAccel): 5, 6, 7 likewise.
set terminal pngcairo size 1500,560 font "DejaVu Sans,20" linewidth 2
set output outfile
set multiplot layout 1,2
set logscale x 10
set format x "10^{%T}"
set xrange [2000:1.5e6]
set xlabel "triangles"
set key top left box opaque
set grid

set title "SAH build"
set yrange [0.5:3000]
set logscale y 10
set format y "10^{%T}"
set ylabel "build time (ms)"
plot datafile using 1:2 with linespoints pt 7 ps 1.5 title "BVHAccel", \
     datafile using 1:5 with linespoints pt 5 ps 1.5 title "FastBVHAccel"

set title "Tracing, single-threaded"
unset logscale y
set format y "%g"
set yrange [0:24]
set ylabel "Mrays/s"
set key top right font ",17"
plot datafile using 1:3 with linespoints pt 7 ps 1.5 lc 1 title "BVHAccel, camera", \
     datafile using 1:6 with linespoints pt 5 ps 1.5 lc 2 title "FastBVHAccel, camera", \
     datafile using 1:4 with linespoints pt 7 ps 1.5 lc 1 dt 2 title "BVHAccel, incoherent", \
     datafile using 1:7 with linespoints pt 5 ps 1.5 lc 2 dt 2 title "FastBVHAccel, incoherent"
unset multiplot
