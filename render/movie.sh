#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# render/movie.sh - turns a directory of frames (frame_NNNN.png, as
# `sph-render RUN -o DIR` writes them) into an MP4 video with ffmpeg:
# H.264, yuv420p (what browsers and presentation software play), FPS frames
# per second, in name order. `make movie` runs it on frames/.
#   render/movie.sh FRAMES_DIR OUT.mp4 [FPS]        (FPS default 25)
# Without ffmpeg (FFMPEG names the program, default ffmpeg) it says what to
# install and exits 3; a missing or empty frame directory exits 1; bad
# arguments exit 2.
set -eu
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: $0 FRAMES_DIR OUT.mp4 [FPS]" >&2
  exit 2
fi
dir=$1 out=$2 fps=${3:-25}
case $fps in
  ''|*[!0-9]*|0) echo "$0: FPS must be a whole number above 0, not '$fps'" >&2; exit 2 ;;
esac
case $out in
  *.mp4|*.MP4) ;;
  *) echo "$0: the video is an .mp4 file, not '$out'" >&2; exit 2 ;;
esac
ffmpeg=${FFMPEG:-ffmpeg}
if ! command -v "$ffmpeg" > /dev/null 2>&1; then
  echo "$0: making a video needs ffmpeg, which is not installed: apt-get install ffmpeg" >&2
  exit 3
fi
if ! ls "$dir"/frame_*.png > /dev/null 2>&1; then
  echo "$0: no frames (frame_*.png) in '$dir': make them first, e.g. sph-render out/martin_moyce -o $dir" >&2
  exit 1
fi
tmp="$out.tmp.mp4"
trap 'rm -f "$tmp"' EXIT
# pad to even sizes (yuv420p needs them); frames in name order
"$ffmpeg" -hide_banner -loglevel error -y -framerate "$fps" -pattern_type glob \
  -i "$dir/frame_*.png" -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p \
  -movflags +faststart "$tmp"
mv "$tmp" "$out"
trap - EXIT
n=$(ls "$dir"/frame_*.png | wc -l)
echo "$0: wrote $out ($n frames at $fps per second)"
