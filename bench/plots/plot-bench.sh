#!/usr/bin/env bash
# Plots the CSVs of scripts/bench.sh with gnuplot (PNG, 900x560):
#   quality_<display>.png   ms/frame (log) vs PSNR corrected for the reference's noise, direct path vs quilt points
#                           (from quality_adaptive.csv, if present: quality_adaptive_<display>.png with the adaptive
#                           refinement points too)
#   traversal_mrays.png     Mrays/s per mesh and ray set: holotrace GPU, Embree rtcIntersect1/rtcOccluded1, 8-wide
# Usage: bench/plots/plot-bench.sh DIR   (DIR holds quality.csv and traversal_throughput.csv)
set -euo pipefail
dir="${1:?usage: plot-bench.sh DIR}"
[[ "$dir" == "-h" || "$dir" == "--help" ]] && { sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0; }
[[ -f "$dir/quality.csv" && -f "$dir/traversal_throughput.csv" ]] || { echo "plot-bench.sh: CSVs missing in $dir" >&2; exit 1; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

# --- ms/frame vs PSNR, one PNG per display (quality.csv: lenticular displays; quality_models.csv, if present: the
# projector-array and integral displays, direct path only) ------------------------------------------------------------
for csv in "$dir/quality.csv" "$dir/quality_models.csv" "$dir/quality_adaptive.csv"; do
[[ -f "$csv" ]] || continue
prefix=quality; [[ "$csv" == *quality_adaptive.csv ]] && prefix=quality_adaptive
for display in $(awk -F, 'NR > 1 { print $1 }' "$csv" | sort -u); do
  slug="$(basename "$display" .json | sed 's/^builtin://; s/[^A-Za-z0-9_-]/_/g')"
  awk -F, -v d="$display" '$1 == d && $2 == "direct" { print $9, $12, $3 }' "$csv" | sort -g > "$tmp/direct"
  plots="'$tmp/direct' using 1:2 with linespoints lw 2 pt 7 title 'direct (per-subpixel rays)', \
         '' using 1:2:(sprintf('%d spp', \$3)) with labels offset 0,1 notitle"
  awk -F, -v d="$display" '$1 == d && $2 == "adaptive" { print $9, $12, $3, $14, $15 }' "$csv" | sort -g > "$tmp/adaptive"
  if [[ -s "$tmp/adaptive" ]]; then
    plots="$plots, '$tmp/adaptive' using 1:2 with points pt 9 ps 1.6 title 'adaptive (base spp + refine spp at contrast)', \
           '' using 1:2:(sprintf('%d+%d@%.2f', \$3, \$4, \$5)) with labels offset 0,-1 font ',8' notitle"
  fi
  n=0
  for key in $(awk -F, -v d="$display" '$1 == d && $2 == "quilt" { gsub(/ /, "_", $4); print $4 "|" $5 }' "$csv" | sort -u); do
    quilt="${key%%|*}"; filter="${key##*|}"; n=$((n + 1))
    awk -F, -v d="$display" -v q="${quilt//_/ }" -v f="$filter" '$1 == d && $2 == "quilt" && $4 == q && $5 == f { print $9, $12, $3 }' \
      "$csv" | sort -g > "$tmp/quilt$n"
    plots="$plots, '$tmp/quilt$n' using 1:2 with linespoints pt $((n + 3)) title 'quilt ${quilt//_/ } $filter'"
  done
  gnuplot <<GP
set terminal pngcairo size 900,680 font ",10" noenhanced
set output "$dir/${prefix}_$slug.png"
set title "$display: time vs error (reference: direct path, high spp; PSNR corrected for reference noise)"
set xlabel "ms / frame (render wall time incl. readback; quilt interleave not counted), log scale"
set ylabel "PSNR vs reference (dB, sRGB)"
set logscale x 2
set grid
set key below box
plot $plots
GP
done
done

# --- Mrays/s ours vs Embree per mesh and ray set ----------------------------------------------------------------------
awk -F, 'NR > 1 { n = split($1, p, "/"); m = p[n]; sub(/\.[a-z]+$/, "", m); print m "/" $3, $6, $7, $8 }' \
  "$dir/traversal_throughput.csv" > "$tmp/mrays"
gnuplot <<GP
set terminal pngcairo size 1100,600 font ",10" noenhanced
set output "$dir/traversal_mrays.png"
set title "Traversal throughput on the same rays (holotrace GPU kernel vs Embree 3 CPU)"
set ylabel "Mrays/s"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set xtics rotate by -35 scale 0
set rmargin 10
set bmargin 7
set grid ytics
set key top left
set yrange [0:*]
set offsets 0, 0, graph 0.12, 0
plot "$tmp/mrays" using 2:xtic(1) title "holotrace GPU (lavapipe)", \
     "" using 3 title "Embree rtcIntersect1/rtcOccluded1", \
     "" using 4 title "Embree rtcIntersect8/rtcOccluded8"
GP
echo "plot-bench.sh: PNGs in $dir"
