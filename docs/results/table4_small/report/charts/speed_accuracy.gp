# Drawn by `layers report`; redraw with: gnuplot speed_accuracy.gp
set terminal pngcairo size 900,600 font 'Sans,10' noenhanced
if (!exists('out')) out = 'speed_accuracy.png'
set output out
set title 'Accuracy against speed'
set xlabel 'ms per predicted frame (log scale)'
set ylabel 'mean Euclidean error (mm)'
set logscale x
set yrange [0:*]
set grid
set key outside right top
set datafile missing 'NaN'
set offsets graph 0.15, graph 0.35, graph 0.15, graph 0.15
plot 'speed_accuracy_front.dat' using 1:2 with steps dt 2 lw 1.5 lc rgb '#999999' title 'Pareto front', \
     'speed_accuracy_front.dat' using 1:2 with points pt 6 ps 3.2 lw 2 lc rgb '#d62728' title 'on the front', \
     'speed_accuracy_runs.dat' index 0 using 1:2 with points pt 7 ps 1.8 lc rgb '#1f77b4' title 'static', \
     'speed_accuracy_runs.dat' index 1 using 1:2 with points pt 7 ps 1.8 lc rgb '#ff7f0e' title 'skinned', \
     'speed_accuracy_runs.dat' index 2 using 1:2 with points pt 7 ps 1.8 lc rgb '#2ca02c' title 'deepsd/seed-0', \
     'speed_accuracy_runs.dat' index 3 using 1:2 with points pt 7 ps 1.8 lc rgb '#d62728' title 'deepsd/seed-1', \
     'speed_accuracy_runs.dat' index 4 using 1:2 with points pt 7 ps 1.8 lc rgb '#9467bd' title 'deepsd/seed-2', \
     'speed_accuracy_runs.dat' index 5 using 1:2 with points pt 7 ps 1.8 lc rgb '#8c564b' title 'deepsd+/seed-0', \
     'speed_accuracy_runs.dat' index 6 using 1:2 with points pt 7 ps 1.8 lc rgb '#e377c2' title 'deepsd+/seed-1', \
     'speed_accuracy_runs.dat' index 7 using 1:2 with points pt 7 ps 1.8 lc rgb '#7f7f7f' title 'deepsd+/seed-2', \
     'speed_accuracy_runs.dat' index 8 using 1:2 with points pt 7 ps 1.8 lc rgb '#bcbd22' title 'layersnet/seed-0', \
     'speed_accuracy_runs.dat' index 9 using 1:2 with points pt 7 ps 1.8 lc rgb '#17becf' title 'layersnet/seed-1', \
     'speed_accuracy_runs.dat' index 10 using 1:2 with points pt 7 ps 1.8 lc rgb '#1f77b4' title 'layersnet/seed-2', \
     'speed_accuracy_runs.dat' index 11 using 1:2 with points pt 7 ps 1.8 lc rgb '#ff7f0e' title 'layersnet+/seed-0', \
     'speed_accuracy_runs.dat' index 12 using 1:2 with points pt 7 ps 1.8 lc rgb '#2ca02c' title 'layersnet+/seed-1', \
     'speed_accuracy_runs.dat' index 13 using 1:2 with points pt 7 ps 1.8 lc rgb '#d62728' title 'layersnet+/seed-2', \
     'speed_accuracy_runs.dat' index 14 using 1:2 with points pt 7 ps 1.8 lc rgb '#9467bd' title 'mgnet-follow/seed-0', \
     'speed_accuracy_runs.dat' index 15 using 1:2 with points pt 7 ps 1.8 lc rgb '#8c564b' title 'mgnet-follow/seed-1', \
     'speed_accuracy_runs.dat' index 16 using 1:2 with points pt 7 ps 1.8 lc rgb '#e377c2' title 'mgnet-follow/seed-2', \
     'speed_accuracy_runs.dat' index 17 using 1:2 with points pt 7 ps 1.8 lc rgb '#7f7f7f' title 'layersnet-body-gate/seed-0', \
     'speed_accuracy_runs.dat' index 18 using 1:2 with points pt 7 ps 1.8 lc rgb '#bcbd22' title 'layersnet-body-gate/seed-1', \
     'speed_accuracy_runs.dat' index 19 using 1:2 with points pt 7 ps 1.8 lc rgb '#17becf' title 'layersnet-body-gate/seed-2', \
     'speed_accuracy_runs.dat' using 1:2:3 with labels offset char 1.5,0.9 left notitle, \
     'speed_accuracy_bench.dat' index 0 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#1f77b4' title 'static: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 0 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#1f77b4' notitle, \
     'speed_accuracy_bench.dat' index 1 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#ff7f0e' title 'skinned: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 1 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#ff7f0e' notitle, \
     'speed_accuracy_bench.dat' index 2 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#2ca02c' title 'deepsd/seed-0: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 2 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#2ca02c' notitle, \
     'speed_accuracy_bench.dat' index 3 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#d62728' title 'deepsd/seed-1: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 3 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#d62728' notitle, \
     'speed_accuracy_bench.dat' index 4 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#9467bd' title 'deepsd/seed-2: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 4 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#9467bd' notitle, \
     'speed_accuracy_bench.dat' index 5 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#8c564b' title 'deepsd+/seed-0: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 5 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#8c564b' notitle, \
     'speed_accuracy_bench.dat' index 6 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#e377c2' title 'deepsd+/seed-1: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 6 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#e377c2' notitle, \
     'speed_accuracy_bench.dat' index 7 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#7f7f7f' title 'deepsd+/seed-2: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 7 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#7f7f7f' notitle, \
     'speed_accuracy_bench.dat' index 8 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#bcbd22' title 'layersnet/seed-0: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 8 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#bcbd22' notitle, \
     'speed_accuracy_bench.dat' index 9 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#17becf' title 'layersnet/seed-1: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 9 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#17becf' notitle, \
     'speed_accuracy_bench.dat' index 10 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#1f77b4' title 'layersnet/seed-2: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 10 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#1f77b4' notitle, \
     'speed_accuracy_bench.dat' index 11 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#ff7f0e' title 'layersnet+/seed-0: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 11 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#ff7f0e' notitle, \
     'speed_accuracy_bench.dat' index 12 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#2ca02c' title 'layersnet+/seed-1: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 12 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#2ca02c' notitle, \
     'speed_accuracy_bench.dat' index 13 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#d62728' title 'layersnet+/seed-2: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 13 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#d62728' notitle, \
     'speed_accuracy_bench.dat' index 14 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#9467bd' title 'mgnet-follow/seed-0: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 14 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#9467bd' notitle, \
     'speed_accuracy_bench.dat' index 15 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#8c564b' title 'mgnet-follow/seed-1: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 15 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#8c564b' notitle, \
     'speed_accuracy_bench.dat' index 16 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#e377c2' title 'mgnet-follow/seed-2: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 16 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#e377c2' notitle, \
     'speed_accuracy_bench.dat' index 17 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#7f7f7f' title 'layersnet-body-gate/seed-0: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 17 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#7f7f7f' notitle, \
     'speed_accuracy_bench.dat' index 18 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#bcbd22' title 'layersnet-body-gate/seed-1: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 18 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#bcbd22' notitle, \
     'speed_accuracy_bench.dat' index 19 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#17becf' title 'layersnet-body-gate/seed-2: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 19 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#17becf' notitle
