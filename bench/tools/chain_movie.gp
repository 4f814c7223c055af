# The chain's motion as an animated GIF (scripts/figures): the frames of
# chain_movie (PREFIX_frames.dat, one data block per frame, the side view
# x-z). Call: gnuplot -e "prefix='chain_movie'; out='chain.gif'" chain_movie.gp
if (!exists("prefix")) prefix = "chain_movie"
if (!exists("out")) out = "chain_movie.gif"
stats prefix."_frames.dat" using 1 nooutput
nframes = STATS_blocks
set terminal gif animate delay 4 loop 0 size 420,360 font ",9"
set output out
set size ratio -1
set xrange [-6.5:6.5]
set yrange [-6.5:0.8]
set xlabel "x [m]"
set ylabel "z [m]"
set grid lc rgb "#dddddd"
unset key
set object 1 rect from -0.25,0 to 0.25,0.25 fc rgb "#555555" fs solid noborder
do for [i = 0:nframes - 1] {
  set title sprintf("6-rod chain, BDF with error control   t = %.2f s", i * 0.04)
  plot prefix."_frames.dat" index i with linespoints lw 3 pt 7 ps 1.0 lc rgb "#1f5fa8"
}
