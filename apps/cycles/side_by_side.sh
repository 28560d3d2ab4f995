#!/usr/bin/env bash
# rtweekend side by side with Blender Cycles (CPU, Embree, no denoiser) at equal wall time.
#
#   apps/cycles/side_by_side.sh [OUTDIR]        (default /tmp/cycles_side_by_side)
#
# For the book-1 cover (400x225) and book 3's final Cornell box (300x300):
#   1. converged references, cached in OUTDIR: Cycles' own (REF_SPP samples, default 4096) and
#      rtweekend's own, rendered with its defaults and seed 999 at OUR_REF_SPP samples (default
#      32768 for the cover, 16384 for the Cornell box), or $COVER_REF / $CORNELL_REF if that file
#      exists. (Until 2026-11-25 the cover's was the book's 6144-spp image: its own noise was
#      then 40 % of our MSE at 256 Cycles spp.)
#   2. Cycles at CYCLES_SPP (default "16 64 256") samples on THREADS (default 2) threads: the time
#      of its render call (scene sync + BVH + render; Blender's start and the Python scene build
#      are not counted) and its MSE against the Cycles reference;
#   3. right after each Cycles render, rtweekend (build/apps/render, default settings, THREADS
#      threads) at the sample count its speed so far predicts for the same time, then once more
#      corrected by the time that took (process wall time, scene loading included); its sample
#      count at the Cycles time follows from those two renders' seconds per sample, and its MSE
#      there is interpolated log-log in spp between the rtweekend renders on either side
#      (interleaved, so that the shared machine's drift hits both renderers alike);
#   4. a table (stdout and OUTDIR/side_by_side.md) and CSVs: OUTDIR/side_by_side.csv (one row per
#      scene and Cycles sample count) and OUTDIR/runs.csv (every render).
# MSE is linear (radiance), from `compare IMG REF`'s first line: linear rmse X -> MSE = X^2. Each
# MSE includes its reference's own noise. The "floor" columns estimate that noise as the MSE of 16
# spp of the reference's own algorithm times 16 / the reference's sample count (Cycles: its 16-spp
# run; the cover's reference is the book's code: rtweekend's bsdf estimator with independent
# numbers) and the last ratio is of the MSEs less their floors.
# Needs: blender (Debian 12: apt-get install blender; 3.4.1 tested), python3, and the project's
# build (cmake --build build): build/apps/render and build/apps/compare. Not part of CI.
# Environment: BLENDER, BUILD (dir of render/compare), THREADS, CYCLES_SPP, REF_SPP, OUR_REF_SPP,
# COVER_REF, CORNELL_REF,
# LADDER_MAX (most rtweekend spp, default 65536), NICE (a command prefix, e.g. "nice -n 19"),
# CYCLES_ARGS (more options for cycles_scene.py, e.g. "--glass schlick"; the cached Cycles
# references are then the wrong ones: use another OUTDIR), SCENES (which to run: "cover cornell",
# the default, or one of them).
# A full run (2 threads, references not cached) takes an hour or more; with them cached, 6-10 minutes.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
out="${1:-/tmp/cycles_side_by_side}"
BLENDER="${BLENDER:-blender}"
BUILD="${BUILD:-$root/build/apps}"
THREADS="${THREADS:-2}"
CYCLES_SPP="${CYCLES_SPP:-16 64 256}"
REF_SPP="${REF_SPP:-4096}"
OUR_REF_SPP="${OUR_REF_SPP:-}"
COVER_REF="${COVER_REF:-}"
CORNELL_REF="${CORNELL_REF:-}"
LADDER_MAX="${LADDER_MAX:-65536}"
NICE="${NICE:-}"
CYCLES_ARGS="${CYCLES_ARGS:-}"
SCENES="${SCENES:-cover cornell}"
case " $SCENES " in *" cover "*|*" cornell "*) ;; *) echo "side_by_side.sh: SCENES='$SCENES' names neither cover nor cornell" >&2; exit 1;; esac
want() { case " $SCENES " in *" $1 "*) return 0;; esac; return 1; }
mkdir -p "$out"
runs="$out/runs.csv"
echo "scene,renderer,kind,spp,seconds,mse,process_seconds,file" > "$runs"

for tool in render compare; do
    [ -x "$BUILD/$tool" ] || { echo "side_by_side.sh: $BUILD/$tool not found (build the project first)" >&2; exit 1; }
done
command -v "$BLENDER" > /dev/null || { echo "side_by_side.sh: $BLENDER not found (apt-get install blender)" >&2; exit 1; }

now() { date +%s.%N; }
elapsed() { python3 -c "import sys; print('%.4f' % (float(sys.argv[2]) - float(sys.argv[1])))" "$1" "$2"; }

# mse IMG REF: the linear MSE (first line of compare: "linear rmse X ...").
mse() {
    "$BUILD/compare" "$1" "$2" | awk 'NR == 1 && $1 == "linear" && $2 == "rmse" { printf "%.6e\n", $3 * $3; ok = 1 }
                                      END { if (!ok) exit 1 }'
}

# cycles SCENE WIDTH SPP SEED OUT: renders; prints the render call's seconds; the log goes to OUT.log.
cycles() {
    local t0 t1 secs
    t0=$(now)
    $NICE "$BLENDER" -b --factory-startup --python "$here/cycles_scene.py" -- "$1" --width "$2" --spp "$3" \
        --seed "$4" --threads "$THREADS" $CYCLES_ARGS -o "$5" > "$5.log" 2>&1 || { cat "$5.log" >&2; return 1; }
    t1=$(now)
    secs=$(sed -n 's/^CYCLES_RESULT .* seconds=\([0-9.]*\) .*/\1/p' "$5.log")
    [ -n "$secs" ] || { cat "$5.log" >&2; return 1; }
    echo "$secs $(elapsed "$t0" "$t1")"
}

# ours SCENE WIDTH SPP OUT [extra args]: renders; prints the process's wall seconds.
ours() {
    local scene="$1" width="$2" spp="$3" o="$4" t0 t1
    shift 4
    t0=$(now)
    $NICE "$BUILD/render" "$scene" --width "$width" --spp "$spp" --threads "$THREADS" "$@" -o "$o" 2> "$o.log" ||
        { cat "$o.log" >&2; return 1; }
    t1=$(now)
    elapsed "$t0" "$t1"
}

summary="$out/side_by_side.csv"
echo "scene,cycles_spp,cycles_seconds,cycles_mse,rtweekend_spp_equal_time,rtweekend_mse_equal_time,mse_ratio_cycles_over_rtweekend,cycles_ref_floor,rtweekend_ref_floor,ratio_above_floors" > "$summary"

run_scene() {
    local name="$1" scene="$2" width="$3" our_ref="$4" our_ref_spp="$5" res secs wall m
    shift 5  # the rest: render options of the algorithm that made rtweekend's reference
    echo "== $name: $scene at width $width, $THREADS threads" >&2

    # 1. references
    local cref="$out/cycles_ref_${name}_${REF_SPP}spp.pfm"
    if [ ! -s "$cref" ]; then
        echo "   Cycles reference, $REF_SPP spp (cached afterwards in $cref)..." >&2
        res=$(cycles "$scene" "$width" "$REF_SPP" 12345 "$cref")
        read -r secs wall <<< "$res"
        echo "$name,cycles,reference,$REF_SPP,$secs,,$wall,$cref" >> "$runs"
    fi
    if [ ! -s "$our_ref" ]; then
        echo "   rtweekend reference, $our_ref_spp spp seed 999 (cached afterwards in $our_ref)..." >&2
        secs=$(ours "$scene" "$width" "$our_ref_spp" "$our_ref" --seed 999)
        echo "$name,rtweekend,reference,$our_ref_spp,$secs,,$secs,$our_ref" >> "$runs"
    fi
    echo "   references: Cycles $cref, rtweekend $our_ref" >&2
    # How far apart the two converged images are (the mapping's differences; compare's bias is the
    # difference of the image means, per channel).
    "$BUILD/compare" "$cref" "$our_ref" | head -1 | sed "s/^/$name: Cycles reference vs rtweekend's: /" > "$out/refs_$name.txt"
    sed 's/^/   /' "$out/refs_$name.txt" >&2
    m=$(mse "$cref" "$our_ref")
    echo "$name,both,references,,,$m,,$cref vs $our_ref" >> "$runs"

    # 2.-3. Cycles, each run followed at once by rtweekend at the sample count its speed so far
    # predicts for the same time, then once more corrected by the time that took (interleaved, so
    # that the shared machine's drift hits both alike).
    local rate spp n img
    img="$out/rtweekend_${name}_16spp.pfm"
    secs=$(ours "$scene" "$width" 16 "$img")
    m=$(mse "$img" "$our_ref")
    echo "$name,rtweekend,run,16,$secs,$m,$secs,$img" >> "$runs"
    rate=$(python3 -c "import sys; print(float(sys.argv[1]) / 16)" "$secs")
    # The reference's own noise: 16 spp of its algorithm, scaled by 16 / its sample count.
    if [ $# -gt 0 ]; then
        img="$out/rtweekend_${name}_16spp_refalgo.pfm"
        secs=$(ours "$scene" "$width" 16 "$img" "$@")
        m=$(mse "$img" "$our_ref")
    fi
    echo "$name,rtweekend,floor,$our_ref_spp,,$m,,$img" >> "$runs"
    for spp in $CYCLES_SPP; do
        img="$out/cycles_${name}_${spp}spp.pfm"
        res=$(cycles "$scene" "$width" "$spp" 1 "$img")
        read -r secs wall <<< "$res"
        m=$(mse "$img" "$cref")
        echo "$name,cycles,run,$spp,$secs,$m,$wall,$img" >> "$runs"
        echo "   Cycles $spp spp: $secs s (render call; process $wall s), MSE $m" >&2
        local target="$secs" last=0
        for attempt in 1 2; do
            n=$(python3 -c "import sys; print(max(1, min(int(sys.argv[3]), round(float(sys.argv[1]) / float(sys.argv[2])))))" \
                "$target" "$rate" "$LADDER_MAX")
            [ "$n" = "$last" ] && break
            img="$out/rtweekend_${name}_${n}spp.pfm"
            secs=$(ours "$scene" "$width" "$n" "$img")
            m=$(mse "$img" "$our_ref")
            echo "$name,rtweekend,run,$n,$secs,$m,$secs,$img" >> "$runs"
            echo "   rtweekend $n spp: $secs s, MSE $m" >&2
            rate=$(python3 -c "import sys; print(float(sys.argv[1]) / float(sys.argv[2]))" "$secs" "$n")
            last="$n"
        done
    done

    # 4. equal time
    python3 - "$runs" "$name" "$REF_SPP" >> "$summary" <<'EOF'
import csv, math, sys
runs, name, ref_spp = sys.argv[1], sys.argv[2], int(sys.argv[3])
rows = [r for r in csv.DictReader(open(runs)) if r["scene"] == name and r["kind"] == "run"]
# Each Cycles run with the rtweekend renders made right after it (file order).
cyc = []
for r in rows:
    if r["renderer"] == "cycles":
        cyc.append((int(r["spp"]), float(r["seconds"]), float(r["mse"]), []))
    elif cyc:
        cyc[-1][3].append((int(r["spp"]), float(r["seconds"])))
lad = sorted({int(r["spp"]): float(r["mse"]) for r in rows if r["renderer"] == "rtweekend"}.items())
# The references' own noise, assuming MSE ~ 1/spp: the MSE of 16 spp of the reference's
# algorithm times 16 / the reference's spp (Cycles: its 16-spp run; rtweekend: row "floor").
fl = [r for r in csv.DictReader(open(runs)) if r["scene"] == name and r["kind"] == "floor"][0]
floor_o = float(fl["mse"]) * 16 / int(fl["spp"])
low = min(cyc)
floor_c = low[2] * low[0] / ref_spp  # its lowest-spp run (16 by default)
# rtweekend at the Cycles time t: the sample count its renders right after that Cycles run reach
# in t (their seconds per sample, pooled), and the MSE there, interpolated log-log in spp
# between the rtweekend renders on either side (spp is exact; times are noisy on a shared machine).
def at(t, after):
    rate = sum(sec for _, sec in after) / sum(n for n, _ in after)
    s = t / rate
    i = 0
    while i + 2 < len(lad) and lad[i + 1][0] < s:
        i += 1
    (s0, m0), (s1, m1) = lad[i], lad[i + 1]
    f = (math.log(s) - math.log(s0)) / (math.log(s1) - math.log(s0))
    return s, math.exp(math.log(m0) + f * (math.log(m1) - math.log(m0)))
for spp, t, m, after in sorted(cyc):
    s_o, m_o = at(t, after)
    above_c, above_o = m - floor_c, m_o - floor_o
    ratio_above = above_c / above_o if above_o > 0 and above_c > 0 else float("nan")
    print("%s,%d,%.3f,%.4e,%.0f,%.4e,%.2f,%.2e,%.2e,%.2f" % (name, spp, t, m, s_o, m_o, m / m_o, floor_c, floor_o,
                                                           ratio_above))
EOF
}

# rtweekend's references: its own renders with its defaults (so the floor estimate is the 16-spp
# run's MSE scaled as 1/spp; with Sobol numbers, whose MSE falls faster, an upper bound).
if want cover; then
    n="${OUR_REF_SPP:-32768}"
    ref="$out/rtweekend_ref_cover_400_${n}spp_seed999.pfm"
    [ -n "$COVER_REF" ] && [ -s "$COVER_REF" ] && ref="$COVER_REF"
    run_scene cover "$root/tests/data/rtiow_cover.txt" 400 "$ref" "$n"
fi
if want cornell; then
    n="${OUR_REF_SPP:-16384}"
    ref="$out/rtweekend_ref_cornell_300_${n}spp_seed999.pfm"
    [ -n "$CORNELL_REF" ] && [ -s "$CORNELL_REF" ] && ref="$CORNELL_REF"
    run_scene cornell "$root/tests/data/cornell_final.txt" 300 "$ref" "$n"
fi

python3 - "$summary" "$THREADS" > "$out/side_by_side.md" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| scene | Cycles spp | Cycles s | Cycles MSE | rtweekend spp at equal time | rtweekend MSE at equal time "
      "| ratio (Cycles / rtweekend) | ratio above the references' floors |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for r in rows:
    print("| %s | %s | %.2f | %.3e | %s | %.3e | %.1f | %s |" % (
        r["scene"], r["cycles_spp"], float(r["cycles_seconds"]), float(r["cycles_mse"]),
        r["rtweekend_spp_equal_time"], float(r["rtweekend_mse_equal_time"]),
        float(r["mse_ratio_cycles_over_rtweekend"]), r["ratio_above_floors"]))
print()
print("%s threads; MSE linear, each renderer against its own converged reference." % sys.argv[2])
print()
EOF
for name in cover cornell; do
    if want "$name"; then cat "$out/refs_$name.txt" >> "$out/side_by_side.md"; fi
done
cat "$out/side_by_side.md"
echo "CSV: $summary (summary), $runs (every render)"
