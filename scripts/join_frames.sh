#!/usr/bin/env bash
# Joins a camera path's frames (FRAMES/frame_NNNN.png, from exacity render --path or
# scripts/render_path.sbatch) into an H.264 MP4 with ffmpeg (docs/rendering.md, On a Slurm cluster).
#
#   scripts/join_frames.sh FRAMES FPS OUT.mp4
#
# FPS is the path file's "fps". yuv420p and even sizes, so that common players open it;
# a missing frame (a task that failed) stops the join with its name.
set -euo pipefail

if [ $# -ne 3 ]; then
  echo "usage: $0 FRAMES FPS OUT.mp4" >&2
  exit 2
fi
frames=$1 fps=$2 mp4=$3
command -v ffmpeg >/dev/null || { echo "$0: ffmpeg is not installed (apt-get install ffmpeg)" >&2; exit 2; }
count=$(find "$frames" -maxdepth 1 -name 'frame_[0-9][0-9][0-9][0-9].png' | wc -l)
[ "$count" -gt 0 ] || { echo "$0: $frames: no frame_NNNN.png" >&2; exit 2; }
first=$(find "$frames" -maxdepth 1 -name 'frame_[0-9][0-9][0-9][0-9].png' | sort | head -1)
first=$(basename "$first" .png); first=$((10#${first#frame_}))
for ((n = first; n < first + count; ++n)); do
  name=$(printf '%s/frame_%04d.png' "$frames" "$n")
  [ -f "$name" ] || { echo "$0: $name is missing: render it again (exacity render --frames $n:$n)" >&2; exit 2; }
done
ffmpeg -loglevel error -y -framerate "$fps" -start_number "$first" -i "$frames/frame_%04d.png" \
  -vf "scale=trunc(iw/2)*2:trunc(ih/2)*2" -c:v libx264 -pix_fmt yuv420p -crf 18 "$mp4"
echo "$0: wrote $mp4 ($count frames at $fps fps)"
