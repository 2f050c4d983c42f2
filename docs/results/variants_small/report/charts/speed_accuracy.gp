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
     'speed_accuracy_runs.dat' index 0 using 1:2 with points pt 7 ps 1.8 lc rgb '#1f77b4' title 'layersnet-body-gate', \
     'speed_accuracy_runs.dat' index 1 using 1:2 with points pt 7 ps 1.8 lc rgb '#ff7f0e' title 'layersnet-bones-8ep', \
     'speed_accuracy_runs.dat' index 2 using 1:2 with points pt 7 ps 1.8 lc rgb '#2ca02c' title 'layersnet-bones-gate-8ep', \
     'speed_accuracy_runs.dat' index 3 using 1:2 with points pt 7 ps 1.8 lc rgb '#d62728' title 'layersnet-skin-gate-10ep', \
     'speed_accuracy_runs.dat' using 1:2:3 with labels offset char 1.5,0.9 left notitle, \
     'speed_accuracy_bench.dat' index 0 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#1f77b4' title 'layersnet-body-gate: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 0 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#1f77b4' notitle, \
     'speed_accuracy_bench.dat' index 1 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#ff7f0e' title 'layersnet-bones-8ep: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 1 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#ff7f0e' notitle, \
     'speed_accuracy_bench.dat' index 2 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#2ca02c' title 'layersnet-bones-gate-8ep: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 2 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#2ca02c' notitle, \
     'speed_accuracy_bench.dat' index 3 using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb '#d62728' title 'layersnet-skin-gate-10ep: benchmarked sizes', \
     'speed_accuracy_bench.dat' index 3 using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb '#d62728' notitle
