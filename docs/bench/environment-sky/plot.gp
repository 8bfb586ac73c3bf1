set terminal pngcairo size 1350,420 noenhanced
set datafile separator ','
set logscale xy
set grid
set key bottom left
set multiplot layout 1,3
set xlabel 'samples per pixel'
set ylabel 'rel. RMSE (luminance, ref. noise removed)'
plot for [t in 'balanced uniform-faces balanced-mis global-cdf'] 'bench.csv' using (strcol(1) eq t ? $2 : 1/0):4 with linespoints pointsize 1.5 title t
set xlabel 'GPU time of the shading pass (ms)'
plot for [t in 'balanced uniform-faces balanced-mis global-cdf havran2005'] 'bench.csv' using (strcol(1) eq t ? $3 : 1/0):4 with linespoints pointsize 1.5 title t
unset logscale
set logscale y
set xlabel 'frame (sun +0.01 deg each)'
set ylabel 'frame-to-frame change (rel. RMS)'
set key top right
plot for [t in 'balanced balanced-integer balanced-fresh-seed uniform-faces havran2005'] 'temporal.csv' using (strcol(2) eq t && $1 == 0.01 ? $3 : 1/0):4 with linespoints title t.' (0.01 deg/frame)'
unset multiplot
