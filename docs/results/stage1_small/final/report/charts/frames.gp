# Drawn by `layers report`; redraw with: gnuplot frames.gp
set terminal pngcairo size 850,1446 font 'Sans,10' noenhanced
if (!exists('out')) out = 'frames.png'
set output out
unset border
unset tics
unset key
set style fill solid 1.0 noborder
set size ratio -1
set xrange [-0.43309055:0.575240267]
set yrange [-0.0495539219:1.68133636]
set multiplot layout 4,4 title 'Sequence seq-000001: ground truth and predictions, seen from the front' margins 0.0470588235,0.988235294,0.00691562932,0.955739972 spacing 0,0
set title 'frame 2'
set ylabel 'ground truth'
plot 'frames_0_0.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
set title 'frame 13'
unset ylabel
plot 'frames_0_1.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
set title 'frame 25'
unset ylabel
plot 'frames_0_2.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
set title 'frame 36'
unset ylabel
plot 'frames_0_3.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
set ylabel 'layersnet'
plot 'frames_1_0.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_1_1.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_1_2.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_1_3.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
set ylabel 'static'
plot 'frames_2_0.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_2_1.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_2_2.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_2_3.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
set ylabel 'skinned'
plot 'frames_3_0.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_3_1.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_3_2.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset title
unset ylabel
plot 'frames_3_3.dat' using 1:2:3 with filledcurves closed fillcolor rgb variable
unset multiplot
