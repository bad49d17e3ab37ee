#!/usr/bin/env bash
# The FE contact reference of a gear pair (docs/fe_reference.md): for chosen
# positions of the hybrid model's mesh-stiffness grid, writes a CalculiX deck (gmsh mesh of the
# exact profile, verification/fe_reference), runs ccx and reads the rotation, the mesh stiffness
# and the tooth pairs' forces at the scene's torque back, beside the hybrid model's values, and
# the fillet stress of the loaded teeth and their neighbours.
#
# Usage: bash tools/fe_reference.sh SCENE [options]
#   --mesh NAME         a stage scene's mesh (sun-planet1, planet1-ring)
#   --out DIR           output directory (default fe-reference-out)
#   --grid N            the hybrid model's positions per mesh cycle (default 48)
#   --positions "i j"   grid indices to run (default: every 6th plus both sides of every change
#                       in the number of loaded pairs, i.e. denser at the contact-ratio transitions)
#   --refinement R      divides every FE mesh size (default 1)
#   --penalty K         contact penalty [MPa/mm] (default 1e8)
#   --fillet-size F     element size on the read fillets per module (default 0.025, i.e. m/40;
#                       divided by the refinement too)
#   --jobs J            ccx runs at once (default 1; each single-threaded, nice 10)
#   --keep              keep decks and ccx output (default: only the logs)
#   --crack SPEC        a root crack in the FE model: gear,tooth,side,depth_mm,angle_deg[,start_arc_mm]
#                       (start: ISO 6336-3's 30 deg point); a [[damage.pit]] of SCENE (width 1)
#                       is meshed as a spall. Either writes DIR/fe_damage.csv instead of
#                       fe_reference.csv (no hybrid columns: the hybrid model of the damaged pair
#                       is computed by the test that reads it)
#   --crack-tip-size U  element size at the crack tip [um] (default 10; divided by the refinement)
#   --hybrid-scene FILE the scene of the hybrid run whose rotation the FE steps bracket (default
#                       SCENE; the healthy scene for a crack gives the lower bracket)
#   --te-scale "a,b,.." the FE steps' rotations as multiples of the hybrid's (default 0.9,1.04;
#                       a crack needs an upper step above the cracked pair's rotation)
# Writes DIR/fe_reference.csv (one row per position and tooth pair, appended as runs finish),
# DIR/fe_fillet.csv (one row per position and read tooth: its largest fillet tension and
# compression σ_tt, fillet side σ and arc length from the space centre line, and the FE normal
# force on that tooth) and the hybrid model's own CSV under DIR/hybrid. Needs a build with
# EPICYCLE_WITH_GMSH=ON (the test build); installs Debian's calculix-ccx when ccx is missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${EPICYCLE_BUILD_DIR:-$root/build}"
tool="${EPICYCLE_FE_TOOL:-$build/verification/fe_reference/fe_reference}"
app="$build/app/epicycle"

if [ "${1:-}" = "_one" ]; then  # internal: one position (called through xargs)
  shift
  scene=$1 mesh=$2 out=$3 refinement=$4 penalty=$5 keep=$6 fillet=$7 crack=$8 tip=$9
  scales=${10} damage=${11} index=${12}
  hybrid="$out/hybrid/$(ls "$out/hybrid" | grep '^stiffness_.*\.csv$' | head -1)"
  # Grid positions are the distinct angles of the data rows in file order (compared as strings:
  # "0.000000" would equal an unset variable as a number).
  row=$(awk -F, -v k="$index" '$1 ~ /^-?[0-9]/ { if ($1 "" != last "") { i++; last = $1 }
        if (i - 1 == k) { print; exit } }' "$hybrid")
  [ -n "$row" ] || { echo "fe_reference: no grid position $index in $hybrid" >&2; exit 1; }
  angle=$(echo "$row" | cut -d, -f1)
  te=$(echo "$row" | cut -d, -f5)
  khyb=$(echo "$row" | cut -d, -f4)
  # Two steps bracketing the hybrid model's rotation: the FE answer is interpolated between them
  # (extrapolated, and flagged, if it lies outside).
  rot=$(awk -v t="$te" -v s="$scales" 'BEGIN { n = split(s, f, ",")
        for (i = 1; i <= n; i++) printf "%s%.9g", (i > 1 ? "," : ""), f[i] * t }')
  dir="$out/pos${index}_r${refinement}_k${penalty}_f${fillet}"
  [ -n "$crack" ] && dir="${dir}_t${tip}"
  mkdir -p "$dir"
  meshopt=()
  [ -n "$mesh" ] && meshopt=(--mesh "$mesh")
  [ -n "$crack" ] && meshopt+=(--crack "$crack" --crack-tip-size-um "$tip")
  if [ -f "$dir/time.txt" ] && [ -f "$dir/deck.info" ] && [ -f "$dir/deck.frd" ] && grep -q "Job finished" "$dir/ccx.log" 2>/dev/null; then
    echo "position $index: reading the finished run in $dir"
  else
    "$tool" deck "$scene" "${meshopt[@]}" --angle-deg "$angle" --rotations-urad "$rot" \
      --refinement "$refinement" --penalty "$penalty" --fillet-size-per-module "$fillet" \
      --out "$dir" > "$dir/deck.log"
    (cd "$dir" && OMP_NUM_THREADS=1 /usr/bin/time -f "%e %U" -o time.txt nice -n 10 ccx -i deck \
       > ccx.log 2>&1) || { echo "fe_reference: ccx failed at position $index (see $dir/ccx.log)" >&2; exit 1; }
  fi
  fe=$("$tool" read "$dir")
  fillets=$("$tool" fillets "$dir")
  read -r wall cpu < "$dir/time.txt"
  nodes=$(awk '$1 == "nodes" { print $2 }' "$dir/deck.info")
  elements=$(awk '$1 == "elements" { print $2 }' "$dir/deck.info")
  if [ -n "$damage" ]; then
    # kind and depth [mm] of the damage (crack: its length q; spall: its depth d), then per pair.
    kind=${damage%%:*} depth=${damage#*:}
    echo "$fe" | awk -F, -v idx="$index" -v r="$refinement" -v K="$penalty" -v n="$nodes" \
        -v e="$elements" -v w="$wall" -v c="$cpu" -v kind="$kind" -v q="$depth" -v tip="$tip" '
      { for (j = 8; j + 2 <= NF; j += 3)
          printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", kind, q, idx, $1, r, K,
                 (kind == "crack" ? tip : 0), n, e, w, c, $6, $7, $2, $4, $j, $(j + 1) "," $(j + 2) }
    ' >> "$out/fe_damage.csv"
    [ "$keep" = 1 ] || rm -f "$dir/deck.inp" "$dir/deck.frd" "$dir/deck.12d" "$dir/spooles.out"
    echo "position $index (${angle} deg): done in ${wall} s (ccx CPU ${cpu} s)"
    exit 0
  fi
  # One row per FE tooth pair, with the hybrid model's share of the same teeth (0 if unloaded).
  echo "$fe" | awk -F, -v idx="$index" -v r="$refinement" -v K="$penalty" -v n="$nodes" \
      -v e="$elements" -v w="$wall" -v c="$cpu" -v te="$te" -v kh="$khyb" -v hyb="$hybrid" \
      -v angle="$angle" '
    BEGIN { while ((getline line < hyb) > 0) { split(line, f, ",");
              if (f[1] == angle) share[f[9]] = f[13] } }
    { for (j = 8; j + 2 <= NF; j += 3)
        printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", idx, $1, r, K, n, e, w,
               c, $6, $7, $2, te, $4, kh, $j, $(j + 1), $(j + 2), ($j in share) ? share[$j] : 0 }
  ' >> "$out/fe_reference.csv"
  # One row per read tooth, with the FE normal force on it (the sum over its tooth pairs).
  echo "$fillets" | awk -F, -v idx="$index" -v r="$refinement" -v K="$penalty" -v fs="$fillet" \
      -v n="$nodes" -v c="$cpu" -v fe="$fe" '
    BEGIN { nf = split(fe, f, ","); angle = f[1]
            for (j = 8; j + 2 <= nf; j += 3) { split(f[j], t, "/")
              force[1, t[1]] += f[j + 1]; force[2, t[2]] += f[j + 1] } }
    { printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%.9g\n", idx, angle, r, K, fs, n, c,
             $1, $2, $3, $4, $5, $6, $7, $8, force[$1, $2] + 0 }
  ' >> "$out/fe_fillet.csv"
  [ "$keep" = 1 ] || rm -f "$dir/deck.inp" "$dir/deck.frd" "$dir/deck.12d" "$dir/spooles.out"
  echo "position $index (${angle} deg): done in ${wall} s (ccx CPU ${cpu} s)"
  exit 0
fi

scene="" mesh="" out="fe-reference-out" grid=48 positions="" refinement=1 penalty=1e8 jobs=1 keep=0
fillet=0.025 crack="" tip=10 hybrid_scene="" scales="0.9,1.04"
while [ $# -gt 0 ]; do
  case "$1" in
    --mesh) mesh=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --grid) grid=$2; shift 2 ;;
    --positions) positions=$2; shift 2 ;;
    --refinement) refinement=$2; shift 2 ;;
    --penalty) penalty=$2; shift 2 ;;
    --fillet-size) fillet=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    --crack) crack=$2; shift 2 ;;
    --crack-tip-size) tip=$2; shift 2 ;;
    --hybrid-scene) hybrid_scene=$2; shift 2 ;;
    --te-scale) scales=$2; shift 2 ;;
    -*) echo "fe_reference: unknown option $1" >&2; exit 2 ;;
    *) scene=$1; shift ;;
  esac
done
[ -n "$scene" ] || { sed -n '2,33p' "$0"; exit 2; }
[ -n "$hybrid_scene" ] || hybrid_scene=$scene
# The damage the FE model carries (kind:depth_mm), empty for the healthy pair.
damage=""
[ -n "$crack" ] && damage="crack:$(echo "$crack" | cut -d, -f4)"
if [ -z "$crack" ] && grep -q '^\[\[damage.pit\]\]' "$scene"; then
  damage="spall:$(awk -F= '$1 ~ /^depth_um/ { printf "%.6g", $2 / 1000 }' "$scene")"
fi
if ! command -v ccx > /dev/null; then
  echo "fe_reference: installing calculix-ccx"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends calculix-ccx
fi
[ -x "$tool" ] || cmake --build "$build" --target epicycle_fe_reference_tool -j2
[ -x "$app" ] || cmake --build "$build" --target epicycle -j2
mkdir -p "$out"
out="$(cd "$out" && pwd)"
meshopt=()
[ -n "$mesh" ] && meshopt=(--mesh "$mesh")
if [ ! -d "$out/hybrid" ]; then
  "$app" stiffness "$hybrid_scene" "${meshopt[@]}" --positions "$grid" --cycle 0 --out "$out/hybrid" \
    > "$out/hybrid.log"
fi
hybrid="$out/hybrid/$(ls "$out/hybrid" | grep '^stiffness_.*\.csv$' | head -1)"
if [ -z "$positions" ]; then
  # Loaded pairs per grid position; take every 6th and both sides of each change.
  positions=$(awk -F, -v g="$grid" '$1 ~ /^-?[0-9]/ && $1 "" != last "" { pairs[n++] = $8; last = $1 }
    END { for (i = 0; i < n; i++) { j = (i + 1) % n
            if (i % 6 == 0) pick[i] = 1
            if (pairs[i] != pairs[j]) { pick[i] = 1; pick[j] = 1; pick[(i + 2) % n] = 1 } }
          for (i = 0; i < n; i++) if (pick[i]) printf "%d ", i }' "$hybrid")
fi
[ -f "$out/fe_reference.csv" ] || echo "index,angle_deg,refinement,penalty_MPa_per_mm,nodes,elements,ccx_wall_s,ccx_cpu_s,extrapolated,moment_balance,fe_te_urad,hybrid_te_urad,fe_k_N_per_mm_um,hybrid_k_N_per_mm_um,pair_teeth,fe_pair_force_N,fe_share,hybrid_share" > "$out/fe_reference.csv"
[ -z "$damage" ] || [ -f "$out/fe_damage.csv" ] || echo "damage,depth_mm,index,angle_deg,refinement,penalty_MPa_per_mm,crack_tip_size_um,nodes,elements,ccx_wall_s,ccx_cpu_s,extrapolated,moment_balance,fe_te_urad,fe_k_N_per_mm_um,pair_teeth,fe_pair_force_N,fe_share" > "$out/fe_damage.csv"
[ -f "$out/fe_fillet.csv" ] || echo "index,angle_deg,refinement,penalty_MPa_per_mm,fillet_size_per_module,nodes,ccx_cpu_s,gear,tooth,tension_MPa,tension_side,tension_arc_mm,compression_MPa,compression_side,compression_arc_mm,fe_tooth_force_N" > "$out/fe_fillet.csv"
echo "fe_reference: $scene, positions $positions(refinement $refinement, penalty $penalty)"
for p in $positions; do echo "$p"; done |
  xargs -P "$jobs" -I{} bash "$0" _one "$scene" "$mesh" "$out" "$refinement" "$penalty" "$keep" \
    "$fillet" "$crack" "$tip" "$scales" "$damage" {}
if [ -n "$damage" ]; then echo "fe_reference: wrote $out/fe_damage.csv"
else echo "fe_reference: wrote $out/fe_reference.csv and $out/fe_fillet.csv"; fi
