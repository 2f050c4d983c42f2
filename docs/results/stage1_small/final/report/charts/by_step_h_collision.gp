# Drawn by `layers report`; redraw with: gnuplot by_step_h_collision.gp
set terminal pngcairo size 900,500 font 'Sans,10' noenhanced
if (!exists('out')) out = 'by_step_h_collision.png'
set output out
set title 'H-collision against rollout step'
set xlabel 'rollout step (predicted frames after the ground-truth start)'
set ylabel 'garment vertices behind the body (%)'
set grid
set key outside right top
set datafile missing 'NaN'
set xrange [1:35]
set yrange [0:*]
plot 0.07329439 with lines dt 3 lw 1.5 lc rgb '#555555' title 'ground truth', \
     'by_step.dat' index 0 using 1:3 with lines lw 2 lc rgb '#1f77b4' title 'layersnet', \
     'by_step.dat' index 1 using 1:3 with lines lw 2 lc rgb '#ff7f0e' title 'static', \
     'by_step.dat' index 2 using 1:3 with lines lw 2 lc rgb '#2ca02c' title 'skinned'
