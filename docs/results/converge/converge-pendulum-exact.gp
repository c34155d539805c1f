# Error against substep size: pendulum-exact
# Run gnuplot on this file in its folder: it writes converge-pendulum-exact.png and converge-pendulum-exact.svg. The data is inline, below.
$s0 << EOD
0.016666666666666701 0.54733269812089846 ""
0.0083333333333333506 0.30900912091054811 ""
0.0041666666666666753 0.16491807984429221 ""
0.0020833333333333376 0.085296320100493525 ""
0.0010416666666666688 0.043389389505199626 ""
0.00052083333333333441 0.021884170944720973 ""
0.00026041666666666721 0.010989987344000283 ""
EOD
$s1 << EOD
0.016666666666666701 0.54733269812089846 ""
0.0083333333333333506 0.30900912091054811 ""
0.0041666666666666753 0.16491807984429221 ""
0.0020833333333333376 0.085296320100493525 ""
0.0010416666666666688 0.043389389505199626 ""
0.00052083333333333441 0.021884170944720973 ""
0.00026041666666666721 0.010989987344000283 ""
EOD
$s2 << EOD
0.016666666666666701 0.54733269812089591 ""
0.0083333333333333506 0.30900912091054811 ""
0.0041666666666666753 0.16491807984429221 ""
0.0020833333333333376 0.085296320100493525 ""
0.0010416666666666688 0.043389389505199626 ""
0.00052083333333333441 0.021884170944720973 ""
0.00026041666666666721 0.010989987344000283 ""
EOD
$s3 << EOD
0.016666666666666701 0.0013471519106120807 ""
0.0083333333333333506 0.00033657158766876714 ""
0.0041666666666666753 8.4129388516210394e-05 ""
0.0020833333333333376 2.1031502478301703e-05 ""
0.0010416666666666688 5.2578220316981363e-06 ""
0.00052083333333333441 1.3144775947734265e-06 ""
0.00026041666666666721 3.2865758489521203e-07 ""
EOD
set termoption noenhanced
set title 'Error against substep size: pendulum-exact'
set xlabel 'substep h (s)'
set ylabel 'error (m)'
set logscale x
set format x '%g'
set logscale y
set format y '%.0e'
set grid xtics ytics mxtics mytics lc 'gray80'
set key outside right top box
set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05
if (!exists('outdir')) outdir = '.'
set terminal pngcairo size 1000,640 font ',10' noenhanced
set output outdir.'/'.'converge-pendulum-exact.png'
plot $s0 using 1:2 with linespoints lw 1.5 pt 7 ps 1.2 lc 1 title 'gauss-seidel particle: order 0.991', \
     $s1 using 1:2 with linespoints lw 1.5 pt 5 ps 1.2 lc 2 title 'jacobi particle: order 0.991', \
     $s2 using 1:2 with linespoints lw 1.5 pt 13 ps 1.2 lc 3 title 'xpbd particle: order 0.991', \
     $s3 using 1:2 with linespoints lw 1.5 pt 9 ps 1.2 lc 4 title 'shake particle: order 2', \
     1e-08 with lines dt 2 lw 1.5 lc 'gray40' title 'floor: left out of the fit'
set terminal svg size 1000,640 font ',10' noenhanced background 'white'
set output outdir.'/'.'converge-pendulum-exact.svg'
replot
unset output
