# Drawn by `lab stability --out DIR` (docs/lab.md); run `gnuplot stability.gp` in DIR to redraw.
# Scenes on y, solver settings (method:iterations x substeps) then peers on x.
unset key
set xtics rotate by 90 right font ',8'
set ytics font ',9'
set tics scale 0
set lmargin at screen 0.149009
set rmargin at screen 0.888028
set bmargin at screen 0.2
set tmargin at screen 0.933333
set colorbox user origin screen 0.898363, screen 0.2 size screen 0.0137812, screen 0.733333
set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 back fillcolor rgb '#bdbdbd' fillstyle solid noborder
set arrow from 8.5, graph 0 to 8.5, graph 1 nohead front lw 2 lc rgb 'black'
set arrow from 17.5, graph 0 to 17.5, graph 1 nohead front lw 2 lc rgb 'black'
set arrow from 26.5, graph 0 to 26.5, graph 1 nohead front lw 2 lc rgb 'black'
set arrow from 35.5, graph 0 to 35.5, graph 1 nohead front lw 2 lc rgb 'black'
if (!exists('outdir')) outdir = '.'
do for [format in 'png svg'] {
  if (format eq 'png') { if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1161,750 } else { set terminal png size 1161,750 } }
  if (format eq 'svg') { set terminal svg size 1161,750 }
  set output outdir.'/stability-pass.'.format
  set label 1 'Stability: pass (green), fail (red), not judged (grey)' at screen 0.01, screen 0.966667 left
  set cbrange [0:1]
  set palette defined (0 '#d73027', 0.5 '#bdbdbd', 1 '#1a9850')
  set cbtics ('fail' 0, 'n/a' 0.5, 'pass' 1)
  set palette maxcolors 3
  plot 'stability-pass.dat' matrix rowheaders columnheaders using 1:2:($3 == $3 ? 0.5 : 0):($3 == $3 ? 0.5 : 0):3 with boxxyerror fillstyle solid noborder fillcolor palette
  set output outdir.'/stability-error.'.format
  set label 1 'Stability: log10(value / limit) of the worst criterion: > 0 fails, 3 is 1000 or a blow-up, grey n/a' at screen 0.01, screen 0.966667 left
  set cbrange [-3:3]
  set palette defined (-3 '#2166ac', -1 '#d1e5f0', 0 '#f7f7f7', 0.001 '#fddbc7', 1 '#ef8a62', 3 '#67001f')
  set cbtics autofreq
  set palette maxcolors 0
  plot 'stability-error.dat' matrix rowheaders columnheaders using 1:2:($3 == $3 ? 0.5 : 0):($3 == $3 ? 0.5 : 0):3 with boxxyerror fillstyle solid noborder fillcolor palette
  unset output
}
