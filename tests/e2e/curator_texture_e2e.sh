#!/bin/bash
# A curator's own texture, end to end, as the README's staff guide tells it: `texture new` from a
# photograph-like picture (made here: gradients, blotches, outlined pebbles, noise, JPEG) or from a
# scan (a CSV line of heights, made here), a shipped material and a name and description in the
# five languages; `texture check` passes it; `texture install --token 3` puts it into a staff
# folder and kiosk.toml; the headless visit with that kiosk.toml shows it on token 3, strokes it in
# every style (non-silent WAVs, dented PNGs; texture preview likewise) and says its name with its own cue; over the visitor
# population the tests hold out, its median loudness is within 1 LU of the shipped textures' mean
# (curator_levels_check).
# usage: curator_texture_e2e.sh <sketch-a-scratch> <curator_levels_check> photo|scan
set -u
app=$1
levels=$2
mode=$3
work=$(mktemp -d /tmp/sas-curator-XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
unset DISPLAY WAYLAND_DISPLAY WAYLAND_SOCKET SDL_VIDEODRIVER XDG_RUNTIME_DIR
mkdir -p "$work/staff"
sed "s#^staff_dir = .*#staff_dir = \"$work/staff\"#" "$(dirname "$0")/../../install/kiosk.toml" \
  >"$work/staff/kiosk.toml"
config=$work/staff/kiosk.toml

if [ "$mode" = photo ]; then
  key=river_pebbles
  name_en="river pebbles"
  convert -seed 7 -size 2400x1600 gradient:'#6b4a2b-#d9b38c' \
    \( -size 2400x1600 -seed 7 plasma:fractal -blur 0x3 -colorspace gray \) -compose overlay -composite \
    -fill '#5a3a1e' -stroke '#2e1c0c' -strokewidth 8 \
    -draw "ellipse 500,450 260,170 0,360" -draw "ellipse 1300,700 320,210 0,360" \
    -draw "ellipse 1900,400 200,160 0,360" -draw "ellipse 800,1200 300,190 0,360" \
    -draw "ellipse 1800,1250 250,200 0,360" -blur 0x1.5 -attenuate 0.4 +noise Gaussian \
    -quality 85 "$work/photo.jpg" || fail "ImageMagick could not make the photo"
  source=(--photo "$work/photo.jpg" --material wood)
  texts=(--name "en=$name_en" --description "en=Smooth river pebbles set in a bed of sand."
         --name "de=Flusskiesel" --description "de=Glatte Flusskiesel in einem Bett aus Sand."
         --name "fr=galets de rivière" --description "fr=Des galets lisses posés dans un lit de sable."
         --name "it=ciottoli di fiume" --description "it=Ciottoli lisci di fiume in un letto di sabbia."
         --name "es=cantos rodados" --description "es=Cantos rodados lisos sobre un lecho de arena.")
else
  key=file_scan
  name_en="a scanned file"
  # A profilometer's line across a metal file: teeth every 1.2 mm, 0.15 mm deep, sawtooth-shaped,
  # with a little wear; 0.05 mm per sample.
  awk 'BEGIN { print "# height_mm, 0.05 mm apart"; srand(3);
               for (i = 0; i < 600; i++) { x = i * 0.05; t = x / 1.2 - int(x / 1.2);
                 printf "%.4f\n", 0.15 * t + 0.01 * sin(x * 7.0) + 0.004 * (rand() - 0.5) } }' \
    >"$work/scan.csv"
  # One line of values, as a profilometer exports it.
  paste -sd, <(grep -v '^#' "$work/scan.csv") >"$work/line.csv"
  source=(--scan "$work/line.csv" --scan-step-mm 0.05 --material metal)
  texts=(--name "en=$name_en" --description "en=The teeth of a steel file, measured one by one."
         --name "de=eine abgetastete Feile" --description "de=Die Zähne einer Stahlfeile, einzeln vermessen."
         --name "fr=une lime mesurée" --description "fr=Les dents d'une lime en acier, mesurées une à une."
         --name "it=una lima misurata" --description "it=I denti di una lima d'acciaio, misurati uno a uno."
         --name "es=una lima medida" --description "es=Los dientes de una lima de acero, medidos uno a uno.")
fi

start=$(date +%s)
"$app" texture new "$work/$key" "${source[@]}" "${texts[@]}" --token 3 --config "$config" \
  >"$work/new.log" 2>&1 || { cat "$work/new.log"; fail "texture new exited $?"; }
cat "$work/new.log"
echo "texture new took $(($(date +%s) - start)) s"
for file in texture.toml picture.png height.png; do
  [ -s "$work/$key/$file" ] || fail "texture new wrote no $file"
done
[ "$(identify -format '%wx%h' "$work/$key/picture.png")" = 1920x1080 ] ||
  fail "the picture is not the screen's 1920x1080"
for language in en de fr it es; do
  for part in name description; do
    [ -s "$work/$key/cues/$language/${key}_$part.wav" ] || fail "no $language $part cue"
  done
done

"$app" texture check "$work/$key" --config "$config" --strokes 0 >"$work/check.log" 2>&1 ||
  { cat "$work/check.log"; fail "texture check refused the new texture"; }
cat "$work/check.log"
grep -q "no problems" "$work/check.log" || fail "texture check did not say 'no problems'"
grep -q "felt relief" "$work/check.log" || fail "texture check printed no felt relief"

# The preview: a stroke per style, its WAV and a snapshot with the dent (it differs from the plain
# picture).
"$app" texture preview "$work/$key" --config "$config" --out "$work/preview" >"$work/preview.log" 2>&1 ||
  { cat "$work/preview.log"; fail "texture preview failed"; }
for style in scrape rub roll; do
  grep -q "^stroke ${key}_$style .*loudness_lufs=" "$work/preview/preview.txt" ||
    fail "the preview has no $style stroke"
  [ -s "$work/preview/${key}_$style.wav" ] || fail "the preview wrote no $style WAV"
  # Around the pen's tip at the snapshot (x, y of preview.txt), not the banners elsewhere.
  line=$(grep "^stroke ${key}_$style " "$work/preview/preview.txt")
  x=$(sed 's/.* x=\([0-9]*\).*/\1/' <<<"$line")
  y=$(sed 's/.* y=\([0-9]*\).*/\1/' <<<"$line")
  crop="60x60+$((x - 30))+$((y - 30))"
  convert "$work/preview/$key.png" -crop "$crop" +repage "$work/plain_tip.png"
  convert "$work/preview/${key}_$style.png" -crop "$crop" +repage "$work/dent_tip.png"
  changed=$(compare -metric AE "$work/plain_tip.png" "$work/dent_tip.png" null: 2>&1)
  [ "${changed%% *}" -gt 50 ] 2>/dev/null ||
    fail "the $style snapshot shows no dent at the tip ($changed pixels differ around $x,$y)"
done
echo "ok: texture preview wrote a WAV and a dented snapshot per style"

"$app" texture install "$work/$key" --config "$config" --token 3 >"$work/install.log" 2>&1 ||
  { cat "$work/install.log"; fail "texture install failed"; }
[ -s "$work/staff/textures/$key/texture.toml" ] || fail "nothing installed in the staff folder"
grep -q "^token_3 = \"$key\"" "$config" || fail "kiosk.toml's token_3 is not $key"

"$app" demo --quick --config "$config" --out "$work/out" >"$work/demo.log" 2>"$work/demo.err" ||
  { cat "$work/demo.log" "$work/demo.err"; fail "the headless visit failed"; }
[ -s "$work/demo.err" ] && { cat "$work/demo.err"; fail "the headless visit wrote on stderr"; }
visit=$work/out/visit.txt
for style in scrape rub roll; do
  line=$(grep "^stroke ${key}_$style " "$visit") || fail "the visit did not stroke $key ($style)"
  wav=$(sed 's/.* wav=\([^ ]*\).*/\1/' <<<"$line")
  png=$(sed 's/.* png=\([^ ]*\).*/\1/' <<<"$line")
  [ -s "$work/out/$png" ] || fail "no snapshot $png"
  rms=$(sox "$work/out/$wav" -n remix 1 stat 2>&1 | awk '/RMS +amplitude/ {print $3}')
  awk -v r="$rms" 'BEGIN { exit !(r > 1e-4) }' || fail "$wav is silent (RMS $rms)"
  echo "ok: $key $style stroke: $wav RMS $rms, $png"
done
# Its token is the third: the visit's textures are the tokens' in order.
order=$(grep '^stroke [a-z_]*_scrape ' "$visit" | awk '{print $2}' | sed 's/_scrape$//' | head -4 | tr '\n' ' ')
[ "$order" = "bubble_wrap broken_glass $key cracked_ground " ] ||
  fail "token order is '$order', not token 3 = $key"
grep -q "^cue en ${key}_name .* text=$name_en\$" "$visit" ||
  { grep '^cue' "$visit"; fail "the visit did not say the texture's own name cue"; }
echo "ok: the visit said '$name_en' with its own cue"

"$levels" "$work/staff/textures/$key/texture.toml" --token 3 || fail "its level is not matched"
echo "PASS ($(($(date +%s) - start)) s)"
