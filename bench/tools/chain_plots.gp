# The plots a user looks at (scripts/figures): energy change, constraint
# drift, step size and BDF order over time for the chain of chain_movie,
# generalized-alpha and BDF with error control.
# Call: gnuplot -e "prefix='chain_movie'; out='chain_history.png'" chain_plots.gp
if (!exists("prefix")) prefix = "chain_movie"
if (!exists("out")) out = "chain_history.png"
set terminal pngcairo size 900,720 font ",10"
set output out
set datafile separator ","
set key top left
set multiplot layout 2,2 title "6-rod chain, error control rtol = atol = 1e-6 (chain\\_movie)"
set xlabel "t [s]"
set ylabel "E(t) - E(0) [J]"
set title "energy"
plot prefix."_outputs.csv" using ($2):(strcol(1) eq "gen-alpha" ? $4 : 1/0) every ::1 with lines lw 2 title "gen-alpha (0.9)", \
     "" using ($2):(strcol(1) eq "BDF" ? $4 : 1/0) every ::1 with lines lw 2 title "BDF 1-5"
set logscale y
set format y "10^{%L}"
set ylabel "max_i |Phi_i| [m]"
set title "constraint drift at the outputs (dense output)"
plot prefix."_outputs.csv" using ($2):(strcol(1) eq "gen-alpha" ? $5 : 1/0) every ::1 with lines lw 2 title "gen-alpha (0.9)", \
     "" using ($2):(strcol(1) eq "BDF" ? $5 : 1/0) every ::1 with lines lw 2 title "BDF 1-5"
set ylabel "h [s]"
set title "step size"
plot prefix."_steps.csv" using ($2):(strcol(1) eq "gen-alpha" ? $3 : 1/0) every ::1 with steps lw 1.5 title "gen-alpha (0.9)", \
     "" using ($2):(strcol(1) eq "BDF" ? $3 : 1/0) every ::1 with steps lw 1.5 title "BDF 1-5"
unset logscale y
set format y "%g"
set yrange [0:5.5]
set ytics 1
set ylabel "order"
set title "BDF order"
plot prefix."_steps.csv" using ($2):(strcol(1) eq "BDF" ? $4 : 1/0) every ::1 with steps lw 2 lc 2 title "BDF 1-5"
unset multiplot
