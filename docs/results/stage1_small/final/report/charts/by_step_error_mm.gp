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
plot 'by_step.dat' index 0 using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'layersnet', \
     'by_step.dat' index 1 using 1:2 with lines lw 2 lc rgb '#ff7f0e' title 'static', \
     'by_step.dat' index 2 using 1:2 with lines lw 2 lc rgb '#2ca02c' title 'skinned'
