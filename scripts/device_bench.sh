#!/usr/bin/env bash
# The GPU bench of the device bundle (scripts/device_bundle.sh copies this file into the bundle as
# bench.sh; docs/device-bench.md): one command that measures Tallow on a GPU machine without a
# display or package access and writes DIR/results.json and DIR/results.md.
#
#   bash bench.sh --out DIR [--quick | --sizes full|small] [--budget SECONDS] [--fp32-peak TFLOPS] [--gl egl|osmesa]
#
#   --quick          a few tiny rows, for checking the bundle on a software renderer (the test's run)
#   --sizes small    every row at reduced sizes (llvmpipe runs it in minutes); full: the GPU's sizes
#   --budget S       stop starting rows once S seconds have passed (default 450 for full sizes:
#                    inside 8 minutes with the report; 2400 small, 900 quick); rows not run are
#                    listed as skipped
#   --fp32-peak T    the GPU's FP32 peak in TFLOP/s, when the report cannot derive it from the name
#   --gl             the context of every run (default egl: the device platform first)
#
# It sets its own library and data paths (no TALLOW_* variable needs to be set), renders every row
# as its own `tallow` process under a time limit (so one failing row costs only itself), prints
# progress, and writes the report also when rows fail or it is interrupted. Exit status: 0 when
# every row that ran succeeded, 1 otherwise, 2 for bad arguments or an unusable machine.
set -euo pipefail
# An emptied environment (env -i) has no PATH; the driver's tools come from /usr/local/nvidia.
export PATH="${PATH:-/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin}"
[ -d /usr/local/nvidia/bin ] && PATH="$PATH:/usr/local/nvidia/bin"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

die() { echo "bench.sh: $*" >&2; exit 2; }

out="" mode="full" budget="" peak="" gl="egl"
while [ $# -gt 0 ]; do
  case "$1" in
    --out) [ $# -ge 2 ] || die "--out needs a folder"; out="$2"; shift 2 ;;
    --quick) mode="quick"; shift ;;
    --sizes)
      [ $# -ge 2 ] || die "--sizes needs full or small"
      case "$2" in full|small) mode="$2" ;; *) die "--sizes: \"$2\" is neither full nor small" ;; esac
      shift 2 ;;
    --budget)
      [ $# -ge 2 ] && [[ "$2" =~ ^[0-9]+$ ]] && [ "$2" -ge 1 ] || die "--budget needs a whole number of seconds"
      budget="$2"; shift 2 ;;
    --fp32-peak)
      [ $# -ge 2 ] && [[ "$2" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "--fp32-peak needs a number of TFLOP/s"
      peak="$2"; shift 2 ;;
    --gl)
      [ $# -ge 2 ] || die "--gl needs egl or osmesa"
      case "$2" in egl|osmesa) gl="$2" ;; *) die "--gl: \"$2\" is neither egl nor osmesa" ;; esac
      shift 2 ;;
    -h|--help) sed -n '2,19p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument \"$1\" (see --help)" ;;
  esac
done
[ -n "$out" ] || die "--out DIR is required"
# 450 s leaves the preflight and the report inside 8 minutes on a GPU; llvmpipe's checks of the
# bundle (--quick, --sizes small) run far longer per row and get room to finish every row.
if [ -z "$budget" ]; then
  case "$mode" in full) budget=450 ;; small) budget=2400 ;; quick) budget=900 ;; esac
fi
mkdir -p "$out" 2>/dev/null || die "--out: cannot create $out"
[ -w "$out" ] || die "--out: cannot write to $out"
out="$(cd "$out" && pwd)"
runs="$out/runs"
rm -rf "$runs" "$out/.libs"
mkdir -p "$runs" "$out/.libs"
# Some libraries look under $HOME (NVIDIA's shader cache); an emptied environment has none.
export HOME="${HOME:-$out}"

# --- Libraries ---------------------------------------------------------------------------------
# lib/ holds what Tallow needs that a GPU machine lacks (OpenVDB, Embree, TBB, OpenEXR, …): always
# used. lib/base/ holds libraries most systems have (the C++ runtime, zlib, X11, …): used only for
# those the system lacks or has too old, so that the driver's own libraries keep the system's newer
# copies. The dynamic loader itself says which: LD_TRACE_LOADED_OBJECTS lists each needed library
# as found, "not found", or too old ("version … not found").
libpath="$here/lib:$out/.libs"
for dir in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
  [ -d "$dir" ] && libpath="$libpath:$dir"
done
export LD_LIBRARY_PATH="$libpath${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
resolve_libraries() {
  local binary trace name round
  for round in 1 2 3 4 5 6 7 8; do
    local added=0
    for binary in "$here/bin/tallow" "$here/bin/tallow_bench_report"; do
      trace="$(LD_TRACE_LOADED_OBJECTS=1 "$binary" 2>&1 || true)"
      while read -r name; do
        [ -n "$name" ] || continue
        case "$name" in
          libc.so.*|libm.so.*|ld-linux*) die "the system's C library is older than the bundle needs: $(grep -m1 "$name" <<<"$trace")" ;;
          libEGL.so.1|libGLdispatch.so.0)
            die "$name (libglvnd, the EGL loader) is not installed: the bundle leaves the OpenGL/EGL loaders to the machine (docs/device-bench.md: carry libegl1 and libglvnd0)" ;;
        esac
        [ -e "$out/.libs/$name" ] && die "$name is still unusable after taking the bundle's copy: $(grep -m1 "$name" <<<"$trace")"
        [ -e "$here/lib/base/$name" ] || die "$name is missing and the bundle has no copy (rebuild the bundle): $(grep -m1 "$name" <<<"$trace")"
        ln -s "$here/lib/base/$name" "$out/.libs/$name"
        added=1
      done < <(sed -n -e 's/^[[:space:]]*\([^[:space:]]*\) => not found.*/\1/p' \
                      -e 's/^.*: \/[^:]*\/\([^/:]*\): version .* not found.*/\1/p' <<<"$trace" | sort -u)
    done
    [ "$added" = 0 ] && return 0
  done
  die "could not settle the libraries to load (see $out/.libs)"
}
resolve_libraries
taken="$(cd "$out/.libs" && ls | tr '\n' ',')"
taken="${taken%,}"
echo "bench.sh: libraries: the bundle's lib/, from lib/base: ${taken:-none}, the system's for the rest"

# --- EGL vendor -------------------------------------------------------------------------------
# glvnd finds the driver through vendor files; a driver mounted under /usr/local/nvidia (container
# images) ships its own that the standard folders do not list.
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ "$gl" = egl ] &&
   ! ls /usr/share/glvnd/egl_vendor.d/*.json /etc/glvnd/egl_vendor.d/*.json >/dev/null 2>&1; then
  vendors="$(ls /usr/local/nvidia/share/glvnd/egl_vendor.d/*.json 2>/dev/null | tr '\n' ':' || true)"
  if [ -n "$vendors" ]; then
    export __EGL_VENDOR_LIBRARY_FILENAMES="${vendors%:}"
    echo "bench.sh: EGL vendor files: $__EGL_VENDOR_LIBRARY_FILENAMES"
  fi
fi

export TALLOW_DATA_DIR="$here/data" TALLOW_PRESET_DIR="$here/presets"
# Every OpenGL error into the row's log (asynchronously: timings stay), counted by the report.
export TALLOW_GL_ERRORS=1
tallow="$here/bin/tallow"
report="$here/bin/tallow_bench_report"

# --- Meta: what the report names the run by ------------------------------------------------------
meta="$runs/meta.tsv"
{
  printf 'mode\t%s\n' "$mode"
  printf 'budget_s\t%s\n' "$budget"
  printf 'gl\t%s\n' "$gl"
  printf 'started_utc\t%s\n' "$(date -u +%Y-%m-%dT%H:%M:%SZ)"
  printf 'host\t%s\n' "$(uname -srm)"
  printf 'cpu\t%s\n' "$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n1)"
  printf 'cpu_threads\t%s\n' "$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo '?')"
  printf 'glibc\t%s\n' "$(getconf GNU_LIBC_VERSION 2>/dev/null || echo '?')"
  printf 'bundle_libraries_taken\t%s\n' "$taken"
  [ -n "$peak" ] && printf 'fp32_peak_tflops\t%s\n' "$peak"
  if command -v nvidia-smi >/dev/null 2>&1; then
    # name, driver, memory [MiB], maximum SM clock [MHz] (the report derives the FP32 peak from it).
    smi="$(nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader,nounits 2>/dev/null | head -n1 || true)"
    if [ -n "$smi" ]; then
      IFS=',' read -r n d m c <<<"$smi"
      printf 'nvidia_smi_name\t%s\n' "$(echo $n)"
      printf 'nvidia_smi_driver\t%s\n' "$(echo $d)"
      printf 'nvidia_smi_memory_mib\t%s\n' "$(echo $m)"
      printf 'nvidia_smi_max_sm_clock_mhz\t%s\n' "$(echo $c)"
    fi
  fi
} >"$meta"
rows="$runs/rows.tsv"
printf 'name\tkind\tstatus\texit\tseconds\tcommand\n' >"$rows"

write_report() {
  if "$report" --runs "$runs" --materials "$TALLOW_DATA_DIR/materials.csv" --bundle "$here/bundle.json" --out "$out" \
       >"$runs/report.log" 2>&1; then
    echo "bench.sh: wrote $out/results.json and $out/results.md"
  else
    echo "bench.sh: the report failed: $(tail -n 1 "$runs/report.log")" >&2
    return 1
  fi
}
# Interrupted: the rows done so far still become a report.
trap 'echo "bench.sh: interrupted; reporting the rows done so far" >&2; write_report || true; exit 130' INT TERM

start=$SECONDS
failed=0 index=0 total=0
# Each row: NAME KIND TIMEOUT ARGS… (KIND capture: --out is the row's folder; maps: a JSON in it).
run_row() {
  local name="$1" kind="$2" limit="$3"
  shift 3
  index=$((index + 1))
  local elapsed=$((SECONDS - start))
  local left=$((budget - elapsed))
  local cmd=("$tallow" "$@" --gl "$gl")
  if [ "$kind" = maps ]; then cmd+=(--out "$runs/$name/maps.json"); else cmd+=(--out "$runs/$name"); fi
  local shown="tallow $* --gl $gl"
  if [ "$left" -lt 5 ]; then
    printf '[%2d/%d %3ds] %-24s skipped: the %ss budget is spent\n' "$index" "$total" "$elapsed" "$name" "$budget"
    printf '%s\t%s\tskipped\t\t0\t%s\n' "$name" "$kind" "$shown" >>"$rows"
    return 0
  fi
  limit=$((limit * slow))
  [ "$limit" -gt "$left" ] && limit="$left"
  printf '[%2d/%d %3ds] %-24s %s\n' "$index" "$total" "$elapsed" "$name" "$shown"
  mkdir -p "$runs/$name"
  local t0=$SECONDS rc=0
  if command -v timeout >/dev/null 2>&1; then
    timeout --kill-after=10 "$limit" "${cmd[@]}" >"$runs/$name.log" 2>&1 || rc=$?
  else
    "${cmd[@]}" >"$runs/$name.log" 2>&1 || rc=$?
  fi
  local took=$((SECONDS - t0)) status=ok
  if [ "$rc" = 124 ] || [ "$rc" = 137 ]; then status=timeout; elif [ "$rc" != 0 ]; then status=failed; fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$kind" "$status" "$rc" "$took" "$shown" >>"$rows"
  # The report reads stats.json only; each capture keeps its last frame's PNG to look at, so that
  # a full run's hundreds of frames do not fill the disk.
  if [ "$kind" = capture ] && [ -d "$runs/$name" ]; then
    local last
    last="$(ls "$runs/$name" | grep '^frame_.*\.png$' | tail -n 1 || true)"
    find "$runs/$name" -maxdepth 1 -name 'frame_*' ! -name "${last:-none}" -delete
  fi
  if [ "$status" = ok ]; then
    printf '%22s %s in %ds\n' "" "$status" "$took"
  else
    failed=$((failed + 1))
    printf '%22s %s (exit %s) in %ds: %s\n' "" "$status" "$rc" "$took" "$(tail -n 1 "$runs/$name.log")" >&2
  fi
}

# --- The rows ------------------------------------------------------------------------------------
# Sizes per mode. full: the GPU's; small: the same rows cut down until llvmpipe runs them all in
# minutes; quick: a few rows at toy sizes, one of each kind the report reads.
case "$mode" in
  full)
    size=1024x768 occ_size=1024x1024 maps=512 light=512 field=64
    anim_frames=12 conv_frames=80 conv_accumulate=64 scene_frames=80 dc_frames=3 dc_res="128 256 512"
    gather_k=28 gather_n=45 gather_map=512 gather_repeats=5 occ_n=1000 occ_frames=5 occ_fovs="35 28 22 17 13"
    k=28 n=45 vpls=80 ;;
  small)
    size=160x120 occ_size=128x128 maps=128 light=128 field=48
    anim_frames=3 conv_frames=6 conv_accumulate=3 scene_frames=6 dc_frames=2 dc_res="32 48 64"
    gather_k=4 gather_n=2 gather_map=64 gather_repeats=1 occ_n=4 occ_frames=2 occ_fovs="35 28 22 17 13"
    k=8 n=4 vpls=16 ;;
  quick)
    size=64x48 occ_size=64x64 maps=64 light=64 field=32
    anim_frames=2 conv_frames=4 conv_accumulate=2 scene_frames=0 dc_frames=2 dc_res="32"
    gather_k=2 gather_n=1 gather_map=32 gather_repeats=1 occ_n=1 occ_frames=2 occ_fovs="35 17"
    k=2 n=1 vpls=4 ;;
esac
sizes=(--set "sss.map_size=$maps" --set "sss.light_map_size=$light")
# The bunny and the blob run at their presets' defaults on the GPU (512² maps); llvmpipe needs the
# reduced maps there too. Its rows also take longer than a GPU's time limits allow.
scene_sizes=()
slow=1
if [ "$mode" != full ]; then scene_sizes=("${sizes[@]}"); slow=4; fi
pause="$runs/pause.script"
echo "frame 0 pause" >"$pause"
dc=($dc_res) fovs=($occ_fovs)
total=$((3 + 2 + 2 * ${#dc[@]} + 2 * ${#fovs[@]}))
[ "$scene_frames" -gt 0 ] && total=$((total + 2))

echo "bench.sh: mode $mode, $total rows, budget ${budget}s, context $gl"
# The preflight: one tiny frame, so that a machine without a usable GL 4.5 context stops here with
# the driver's own line instead of failing every row.
run_row preflight capture 120 capture --preset blob --size 32x32 --set method=albedo
if [ "$(tail -n 1 "$rows" | cut -f3)" != ok ]; then
  write_report || true
  echo "bench.sh: no usable OpenGL 4.5 context ($gl): $(tail -n 1 "$runs/preflight.log")" >&2
  exit 2
fi
renderer="$(sed -n 's/.*"GL_RENDERER": "\(.*\)",*$/\1/p' "$runs/preflight/stats.json" | head -n1)"
echo "bench.sh: renderer: $renderer"
case "$renderer" in
  *llvmpipe*|*softpipe*|*swrast*) echo "bench.sh: warning: a software renderer; its times say nothing about a GPU" >&2 ;;
esac

# Most telling first, so that a spent budget drops the least.
paper=(--preset candle --size "$size" "${sizes[@]}" --set "sss.maps=$k" --set "sss.samples=$n" --set "vpl.count=$vpls"
       --set "field.res=$field")
# The candle melting (every frame: field, maps and VPLs from scratch), 30 frames per second.
run_row candle_animated capture 150 capture "${paper[@]}" --frames "$anim_frames" --fps 30
# The candle paused: the maps accumulate for sss.frames frames, then only the camera pass runs.
run_row candle_converged capture 150 capture "${paper[@]}" --frames "$conv_frames" --set "sss.frames=$conv_accumulate" --script "$pause"
# The gather of the maps, the paper's fragment pass against the compute pass, bunny, maps restarted.
for gather in fragment compute; do
  run_row "gather_$gather" maps 120 probe maps --preset bunny --k "$gather_k" --n "$gather_n" --map-size "$gather_map" \
    --repeats "$gather_repeats" --gather "$gather"
done
# Dual contouring of the melting candle at each lattice (shading by albedo only, so that the frame
# is the field passes and the surfaces), by both extraction paths (field.extraction: compute, the
# default, row dc_RES; geometry shaders with transform feedback, row dc_RES_geometry).
for res in "${dc[@]}"; do
  for extraction in compute geometry; do
    name="dc_$res"
    [ "$extraction" = compute ] || name="dc_${res}_$extraction"
    run_row "$name" capture 150 capture --preset candle --size "$size" --set method=albedo --set "field.res=$res" \
      --set "field.extraction=$extraction" --frames "$dc_frames" --fps 30
  done
done
if [ "$scene_frames" -gt 0 ]; then
  run_row bunny capture 90 capture --preset bunny --size "$size" --frames "$scene_frames" --script "$pause" "${scene_sizes[@]}"
  run_row blob capture 90 capture --preset blob --size "$size" --frames "$scene_frames" --fps 30 "${scene_sizes[@]}"
fi
# Cached against no-cache by screen occupancy (the paper's Fig. 11): the chocolate-milk blob
# animated, K = 10, N per map texel or per pixel; occupancy set by the field of view.
for method in radiosity-maps no-cache; do
  for fov in "${fovs[@]}"; do
    run_row "occupancy_${method}_$fov" capture 90 capture --preset blob-chocolate --size "$occ_size" \
      --frames "$occ_frames" --fps 30 --set "method=$method" --set sss.maps=10 --set "sss.samples=$occ_n" \
      --set "camera.fov_deg=$fov" "${sizes[@]}"
  done
done

trap - INT TERM
printf 'finished_s\t%s\n' "$((SECONDS - start))" >>"$meta"
write_report || exit 1
echo "bench.sh: $((SECONDS - start))s, $failed row(s) failed"
[ "$failed" = 0 ]
