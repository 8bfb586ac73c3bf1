set terminal pngcairo size 1000,420 noenhanced
set datafile separator ','
set logscale y
set format y '%g'
set grid
set key outside right
set multiplot layout 1,2
set logscale x
set xlabel 'GPU time of the shading pass per image (ms)'
set ylabel 'NMSE (Eq. 6.7)'
plot for [t in 'scattered structured mrp mc-poisson-24 mc-poisson-40 point hybrid'] 'nmse_by_height.csv' using (strcol(2) eq t ? $7 : 1/0):4 with points pointsize 1 title t
unset logscale x
set xlabel 'height of the light (m)'
set xrange [0:5.6]
plot for [t in 'scattered structured mrp mc-poisson-24 mc-poisson-40 point hybrid'] 'nmse_by_height.csv' using (strcol(2) eq t ? $3 + 0.05 * (strstrt('scattered structured mrp mc-poisson-24 mc-poisson-40 point hybrid', t) % 7) : 1/0):4 with points pointsize 1 notitle
unset multiplot
