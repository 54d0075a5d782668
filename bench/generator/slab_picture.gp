# Renders the slab picture of the filled filter-cake shard from slab_picture's data.
#   gnuplot -e "dir='/tmp/slab'; out='docs/images/filter_cake_slab.png'" bench/generator/slab_picture.gp
# Left: the whole section z = 17.5 mm (sphere sections as circles, bonds of the +-0.7 mm slab as
# segments); right: a zoom on the V-notch tip, where a crack would start.
if (!exists("dir")) dir = "/tmp/slab"
if (!exists("out")) out = "filter_cake_slab.png"
set terminal pngcairo size 1600,800 font "sans,12"
set output out
set multiplot layout 1,2 title "stl\\_fill: filter-cake shard, d = 1.42-1.92 mm, 41,132 spheres, gap 0.7 (coordination 11.05); section z = 17.5 mm"
set size ratio -1
set xlabel "x [mm]"
set ylabel "y [mm]"
unset key
spheres = dir."/spheres.dat"
bonds = dir."/bonds.dat"
set style fill solid 0.35 noborder
set title "section (circles) and bonds with both centres within +-0.7 mm"
set xrange [-50:50]
set yrange [-50:50]
plot spheres using 1:2:3 with circles lc rgb "#3b75af", \
     bonds using 1:2:3:4 with vectors nohead lw 0.5 lc rgb "#202020"
set title "zoom: V-notch tip"
set xrange [8:30]
set yrange [13:35]
set style fill solid 0.35 border lc rgb "#3b75af"
plot spheres using 1:2:3 with circles lc rgb "#3b75af", \
     bonds using 1:2:3:4 with vectors nohead lw 1.2 lc rgb "#202020"
unset multiplot
