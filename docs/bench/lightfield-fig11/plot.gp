set terminal pngcairo size 900,420 noenhanced
set datafile separator ','
set logscale xy
set grid
set key bottom left
set multiplot layout 1,2
set xlabel 'GPU time of the shading pass (ms)'
set ylabel 'rel. RMSE (luminance, ref. noise removed)'
plot for [t in 'restricted-cdf uniform-restricted precomputed-global precomputed-shared granier2003'] 'bench.csv' using (strcol(1) eq t ? $3 : 1/0):4 with linespoints pointsize 1.5 title t
set ylabel 'mean Delta E (CIE76, tone-mapped)'
plot for [t in 'restricted-cdf uniform-restricted precomputed-global precomputed-shared granier2003'] 'bench.csv' using (strcol(1) eq t ? $3 : 1/0):5 with linespoints pointsize 1.5 title t
unset multiplot
