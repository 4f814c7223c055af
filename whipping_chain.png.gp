set terminal pngcairo size 900,540 noenhanced
set output 'whipping_chain.png'
set datafile separator ','
set key autotitle columnhead top left
set title 'Whipping chain, 10 rods: step size of error control (rtol = atol = 1e-06, 748 steps)'
set xlabel 't [s]'
set ylabel 'h [s]'
set logscale y
set grid
plot 'whipping_chain.csv' using 1:2 with linespoints pt 7 ps 0.4 lw 1.5 title 'h(t), adaptive', 0.0004551661356 with lines dt 2 lw 2 title 'fixed h of the same error (2197 steps)'
