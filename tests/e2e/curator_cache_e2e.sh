#!/bin/bash
# Two things `texture new` gets right without measuring them twice:
# - a height map (--height-map: a grey PNG, its brightness the relief) at 8 or at 16 bits makes the
#   same texture; a map in colour, one too small and a flat one are refused;
# - the shipped textures' population medians it trims against (and `texture check` compares with)
#   are kept in a cache (calibration/population_cache.h): the trim made from the cache (the
#   second, 16-bit texture) equals the one measured afresh (the first), the whole [gains] table to
#   the last digit; the cache is not used when what the medians depend on changed (a shipped
#   texture's file, a material file, the program itself), nor when it is damaged or holds another
#   key.
# usage: curator_cache_e2e.sh <sketch-a-scratch> <textures dir>
set -u
app=$1
textures=$2
work=$(mktemp -d /tmp/sas-curator-cache-XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
unset DISPLAY WAYLAND_DISPLAY WAYLAND_SOCKET SDL_VIDEODRIVER XDG_RUNTIME_DIR SAS_DATA_DIR
export SAS_CACHE_DIR=$work/cache
# A relief of blotches as an 8-bit grey PNG, and the same at 16 bits (each value times 257).
convert -size 1600x1000 -seed 3 plasma:fractal -colorspace gray -blur 0x4 -depth 8 "$work/map8.png" &&
  convert "$work/map8.png" -depth 16 -define png:bit-depth=16 -define png:color-type=0 \
    "$work/map16.png" || fail "ImageMagick could not make the maps"
# (identify gives the least depth that holds the values; file reads the PNG header.)
file "$work/map16.png" | grep -q '16-bit grayscale' || fail "map16.png is not 16-bit: $(file "$work/map16.png")"
file "$work/map8.png" | grep -q '8-bit grayscale' || fail "map8.png is not 8-bit: $(file "$work/map8.png")"
texts=()
for language in en de fr it es; do texts+=(--name "$language=blotches" --description "$language=Soft blotches."); done
# A small population: the figures only have to be compared, not to be good.
make() {  # make FOLDER MAP [options]: texture new from the height map
  local folder=$1 map=$2
  shift 2
  "$app" texture new "$folder" --height-map "$map" --relief-mm 0.3 --material wood --population 20 \
    --token 3 "${texts[@]}" "$@" >"$folder.log" 2>&1 || { cat "$folder.log"; fail "texture new $folder failed"; }
}
refused() {  # refused WHAT MAP PATTERN: texture new exits 1 saying PATTERN
  "$app" texture new "$work/refused/blotches" --height-map "$2" --force "${texts[@]}" >"$work/refused.log" 2>&1
  local rc=$?
  [ $rc = 1 ] && grep -q -- "$3" "$work/refused.log" || { cat "$work/refused.log"; fail "$1: exit $rc, not refused with '$3'"; }
  echo "ok: $1 refused: $(grep -- "$3" "$work/refused.log" | head -1 | sed "s#$work/##g")"
}
convert -size 1600x1000 gradient:red-blue "$work/colour.png"
convert "$work/map8.png" -resize 320x200 "$work/small.png"
convert -size 1600x1000 xc:gray40 -depth 16 "$work/flat.png"
mkdir -p "$work/refused"
refused "a height map in colour" "$work/colour.png" "in colour"
refused "a height map too small" "$work/small.png" "too small"
refused "a flat height map" "$work/flat.png" "flat"
gains() { sed -n '/^\[gains\]/,/^\[/p' "$1/texture.toml" | grep -v '^#'; }
levels() { grep 'shipped textures. levels' "$1"; }

mkdir -p "$work/a" "$work/b"
make "$work/a/blotches" "$work/map8.png"
levels "$work/a/blotches.log" | grep -q 'measured, cached in' ||
  { cat "$work/a/blotches.log"; fail "the first texture new did not measure and cache the shipped levels"; }
grep -q '^relief_from = "brightness"' "$work/a/blotches/texture.toml" || fail "the height map's relief is not its brightness"
cached=$(ls "$SAS_CACHE_DIR"/shipped-levels-*-20-1.txt 2>/dev/null | head -1)
[ -s "$cached" ] || fail "no cache file in $SAS_CACHE_DIR"
make "$work/b/blotches" "$work/map16.png"
levels "$work/b/blotches.log" | grep -q 'from the cache' ||
  { cat "$work/b/blotches.log"; fail "the second texture new did not use the cache"; }
cmp "$work/a/blotches/picture.png" "$work/b/blotches/picture.png" ||
  fail "the 8-bit and the 16-bit height map made different pictures"
grep -q '^relief_mm = ' "$work/b/blotches/texture.toml" &&
  [ "$(grep '^relief_mm = ' "$work/a/blotches/texture.toml")" = "$(grep '^relief_mm = ' "$work/b/blotches/texture.toml")" ] ||
  fail "the 8-bit and the 16-bit height map made different reliefs"
echo "ok: the 8-bit and the 16-bit height map made the same picture and $(grep '^relief_mm' "$work/b/blotches/texture.toml")"
gains "$work/a/blotches" >"$work/a.gains"
gains "$work/b/blotches" >"$work/b.gains"
grep -q '^sound_trim_db' "$work/a.gains" || fail "no sound_trim_db in [gains]"
diff "$work/a.gains" "$work/b.gains" || fail "the trim from the cache differs from the measured one"
echo "ok: the trim from the cache equals the measured one: $(grep trim_db "$work/b.gains" | paste -sd' ')"

# texture check's level line (its own population, seed 7): measured, then from the cache, same.
check() {  # check LOG [env...]: texture check of a's texture with 20 strokes on token 3
  local log=$1
  shift
  env "$@" "$app" texture check "$work/a/blotches" --strokes 20 --token 3 >"$log" 2>&1 ||
    { cat "$log"; fail "texture check failed ($log)"; }
}
figure() { grep '^  level over' "$1"; }
check "$work/check1.log"
levels "$work/check1.log" | grep -q 'measured, cached' || { cat "$work/check1.log"; fail "check did not measure"; }
check "$work/check2.log"
levels "$work/check2.log" | grep -q 'from the cache' || { cat "$work/check2.log"; fail "check did not use the cache"; }
[ "$(figure "$work/check1.log")" = "$(figure "$work/check2.log")" ] ||
  fail "the check's level from the cache differs: $(figure "$work/check1.log") / $(figure "$work/check2.log")"
echo "ok: texture check's level from the cache equals the measured one"

measured_again() {  # measured_again WHY LOG: the check measured afresh
  levels "$2" | grep -q 'measured' && ! levels "$2" | grep -q 'from the cache' ||
    { cat "$2"; fail "$1: the stale cache was used"; }
  echo "ok: $1: measured afresh"
}
# A shipped texture changed (a copy of the shipped folders through SAS_DATA_DIR, one trim 3 dB up):
# measured afresh, and the mean the texture is judged against moves.
mkdir -p "$work/data/textures"
cp -r "$textures/bubble_wrap" "$textures/broken_glass" "$textures/wooden_board" \
  "$textures/cracked_ground" "$work/data/textures/"
check "$work/copy.log" SAS_DATA_DIR="$work/data"
levels "$work/copy.log" | grep -q 'from the cache' || { cat "$work/copy.log"; fail "an unchanged copy of the shipped files did not use the cache"; }
sed -i 's/^sound_trim_db = .*/sound_trim_db = 3.0/' "$work/data/textures/broken_glass/texture.toml"
check "$work/changed.log" SAS_DATA_DIR="$work/data"
measured_again "a shipped texture.toml changed" "$work/changed.log"
[ "$(figure "$work/changed.log")" != "$(figure "$work/check1.log")" ] ||
  fail "3 dB more on a shipped texture left the check's figures unchanged"
# A material file changed: the materials come from SAS_DATA_DIR's materials first.
cp -r "$textures/materials" "$work/data/materials"
check "$work/materials.log" SAS_DATA_DIR="$work/data"
check "$work/materials2.log" SAS_DATA_DIR="$work/data"
levels "$work/materials2.log" | grep -q 'from the cache' || { cat "$work/materials2.log"; fail "no cache with the copied materials"; }
sed -i '0,/frequency_hz = [0-9]*,/s//frequency_hz = 700,/' "$work/data/materials/glass.toml"
cmp -s "$textures/materials/glass.toml" "$work/data/materials/glass.toml" && fail "the material edit changed nothing"
check "$work/material_changed.log" SAS_DATA_DIR="$work/data"
measured_again "a material file changed" "$work/material_changed.log"
# The program changed: the same program with one byte more (it still runs) under the same name.
mkdir -p "$work/bin"
cp "$app" "$work/bin/$(basename "$app")"
printf 'x' >>"$work/bin/$(basename "$app")"
app_orig=$app
app=$work/bin/$(basename "$app_orig")
check "$work/program.log"
measured_again "the program changed" "$work/program.log"
app=$app_orig
# A damaged cache (a figure cut off) and one holding another key: measured afresh.
check "$work/warm.log"
file=$(ls "$SAS_CACHE_DIR"/shipped-levels-*-20-7.txt | head -1)
sed -i '$ s/ [^ ]*$//' "$file"
check "$work/damaged.log"
measured_again "a damaged cache file" "$work/damaged.log"
sed -i 's/^key \(.*\) [0-9a-f]*$/key \1 0123456789abcdef/' "$file"
check "$work/other_key.log"
measured_again "a cache file with another key" "$work/other_key.log"
[ "$(figure "$work/other_key.log")" = "$(figure "$work/check1.log")" ] || fail "measured afresh, the figure changed"
echo PASS
