# Time per frame against the number of boxes (W1 uniform workloads), log-log, one line per
# structure. Data: broadphase_vs_n.dat written by bench/broadphase_results.py.
#   gnuplot -e "datafile='build/broadphase_vs_n.dat'; outfile='docs/broadphase_time_vs_n.png'" bench/plot_broadphase.gp
if (!exists("datafile")) datafile = "broadphase_vs_n.dat"
if (!exists("outfile")) outfile = "broadphase_time_vs_n.png"
set terminal pngcairo size 1100,700 noenhanced font ",10"
set output outfile
set logscale xy
set xlabel "boxes N (uniform W1 workload)"
set ylabel "ms per frame (update every box + all pairs)"
set title "Broad phase: time per frame against N (1 thread)"
set key outside right top
set grid
set datafile missing "NaN"
stats datafile nooutput
columns = STATS_columns
plot for [i=2:columns] datafile using 1:i with linespoints title columnheader(i)
