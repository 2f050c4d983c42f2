# Drawn by `layers report`; redraw with: gnuplot by_step_error_mm.gp
set terminal pngcairo size 900,500 font 'Sans,10' noenhanced
if (!exists('out')) out = 'by_step_error_mm.png'
set output out
set title 'error (mm) against rollout step'
set xlabel 'rollout step (predicted frames after the ground-truth start)'
set ylabel 'mean Euclidean error (mm)'
set grid
set key outside right top
set datafile missing 'NaN'
set xrange [1:35]
set yrange [0:*]
plot 'by_step.dat' index 0 using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'static', \
     'by_step.dat' index 1 using 1:2 with lines lw 2 lc rgb '#ff7f0e' title 'skinned', \
     'by_step.dat' index 2 using 1:2 with lines lw 2 lc rgb '#2ca02c' title 'deepsd/seed-0', \
     'by_step.dat' index 3 using 1:2 with lines lw 2 lc rgb '#d62728' title 'deepsd/seed-1', \
     'by_step.dat' index 4 using 1:2 with lines lw 2 lc rgb '#9467bd' title 'deepsd/seed-2', \
     'by_step.dat' index 5 using 1:2 with lines lw 2 lc rgb '#8c564b' title 'deepsd+/seed-0', \
     'by_step.dat' index 6 using 1:2 with lines lw 2 lc rgb '#e377c2' title 'deepsd+/seed-1', \
     'by_step.dat' index 7 using 1:2 with lines lw 2 lc rgb '#7f7f7f' title 'deepsd+/seed-2', \
     'by_step.dat' index 8 using 1:2 with lines lw 2 lc rgb '#bcbd22' title 'layersnet/seed-0', \
     'by_step.dat' index 9 using 1:2 with lines lw 2 lc rgb '#17becf' title 'layersnet/seed-1', \
     'by_step.dat' index 10 using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'layersnet/seed-2', \
     'by_step.dat' index 11 using 1:2 with lines lw 2 lc rgb '#ff7f0e' title 'layersnet+/seed-0', \
     'by_step.dat' index 12 using 1:2 with lines lw 2 lc rgb '#2ca02c' title 'layersnet+/seed-1', \
     'by_step.dat' index 13 using 1:2 with lines lw 2 lc rgb '#d62728' title 'layersnet+/seed-2', \
     'by_step.dat' index 14 using 1:2 with lines lw 2 lc rgb '#9467bd' title 'mgnet-follow/seed-0', \
     'by_step.dat' index 15 using 1:2 with lines lw 2 lc rgb '#8c564b' title 'mgnet-follow/seed-1', \
     'by_step.dat' index 16 using 1:2 with lines lw 2 lc rgb '#e377c2' title 'mgnet-follow/seed-2', \
     'by_step.dat' index 17 using 1:2 with lines lw 2 lc rgb '#7f7f7f' title 'layersnet-body-gate/seed-0', \
     'by_step.dat' index 18 using 1:2 with lines lw 2 lc rgb '#bcbd22' title 'layersnet-body-gate/seed-1', \
     'by_step.dat' index 19 using 1:2 with lines lw 2 lc rgb '#17becf' title 'layersnet-body-gate/seed-2'
