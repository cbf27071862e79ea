#!/bin/bash
# `texture check` on broken curator textures: a good folder (a shipped texture's files under a new
# name, with the other languages' names and descriptions and a name and description cue in each
# language) passes; each broken copy (one fault each, below) exits 1 and reports its fault as
# "<file>:<line>: <key>: <what>" at the line where the fault is (found here with grep on the broken
# file); `texture install` of a broken folder exits 1 and installs nothing.
# usage: curator_check_e2e.sh <sketch-a-scratch> <textures source folder> <built cues folder>
set -u
app=$1
textures=$(cd "$2" && pwd)
cues=$(cd "$3" && pwd)
work=$(mktemp -d /tmp/sas-curator-check-XXXXXX)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

key=dry_riverbed
good=$work/good/$key
mkdir -p "$good"
cp "$textures/cracked_ground/picture.png" "$textures/cracked_ground/height.png" "$good/"
grep -v '^#' "$textures/cracked_ground/texture.toml" >"$good/texture.toml"
cat >>"$good/texture.toml" <<'TOML'

[names]
de = "trockenes Flussbett"
fr = "lit de rivière asséché"
it = "letto di fiume secco"
es = "cauce seco"

[descriptions]
de = "Ein ausgetrocknetes Flussbett voller Risse."
fr = "Un lit de rivière asséché, plein de fissures."
it = "Un letto di fiume secco, pieno di crepe."
es = "Un cauce seco, lleno de grietas."
TOML
for language in en de fr it es; do
  mkdir -p "$good/cues/$language"
  cp "$cues/$language/cracked_ground_name.wav" "$good/cues/$language/${key}_name.wav"
  cp "$cues/$language/cracked_ground_description.wav" "$good/cues/$language/${key}_description.wav"
done

"$app" texture check "$good" --strokes 0 >"$work/good.log" 2>&1
rc=$?
if [ $rc != 0 ] || ! grep -q "no problems" "$work/good.log"; then
  sed 's/^/    /' "$work/good.log"
  echo "FAIL: the good folder is refused (exit $rc): the broken cases below would prove nothing"
  exit 1
fi
echo "ok: the good folder passes"

n=0
# broken <what> <file in the folder> <grep pattern for the line, or a number> <key> <edit...>
broken() {
  local what=$1 file=$2 pattern=$3 key_name=$4
  shift 4
  n=$((n + 1))
  local dir=$work/case$n/$key
  mkdir -p "$work/case$n"
  cp -r "$good" "$dir"
  (cd "$dir" && eval "$@") || { fail "$what: could not make the broken copy"; return; }
  local line=$pattern
  if ! [[ $pattern =~ ^[0-9]+$ ]]; then
    line=$(grep -n -m1 -e "$pattern" "$dir/$file" | cut -d: -f1)
    [ -n "$line" ] || { fail "$what: pattern '$pattern' not in $file"; return; }
  fi
  "$app" texture check "$dir" --strokes 0 >"$work/case$n.log" 2>&1
  local rc=$?
  local want="$dir/$file:$line: $key_name: "
  if [ $rc != 1 ]; then
    fail "$what: exit $rc, want 1"
  elif ! grep -qF -- "$want" "$work/case$n.log"; then
    fail "$what: no line starting '$want'"
    sed 's/^/    /' "$work/case$n.log"
  else
    echo "ok: $what -> $(grep -F -- "$want" "$work/case$n.log" | head -1 | sed "s#$work/##")"
  fi
}

broken "a missing required key" texture.toml 1 name "sed -i '/^name = /d' texture.toml"
broken "an unknown key" texture.toml '^colour' colour "sed -i 's/^relief_mm = /colour = \"red\"\nrelief_mm = /' texture.toml"
broken "a language the kiosk does not know" texture.toml '^xx = ' names.xx "sed -i 's/^de = \"trockenes/xx = \"trockenes/' texture.toml"
broken "a malformed language code" texture.toml '^deu = ' names.deu "sed -i 's/^de = \"trockenes/deu = \"trockenes/' texture.toml"
broken "a language the kiosk speaks left out" texture.toml '^\[descriptions\]' descriptions.fr "sed -i '/^fr = \"Un lit/d' texture.toml"
broken "a description of two sentences" texture.toml '^it = \"Un letto' descriptions.it "sed -i 's/^it = \"Un letto.*/it = \"Un letto. Di fiume secco.\"/' texture.toml"
broken "a picture too small" texture.toml '^picture = ' picture "convert -size 320x180 xc:gray50 picture.png"
broken "a picture that is no image" texture.toml '^picture = ' picture "echo 'not an image' >picture.png"
broken "a height map of another size than the picture" texture.toml '^height_map = ' height_map "convert -size 960x540 xc:gray50 -depth 16 height.png"
broken "a height map in colour" texture.toml '^height_map = ' height_map "convert -size 1920x1080 xc:red height.png"
broken "a NaN in a scan" scan.csv 3 height "printf '0.1, 0.2, 0.3, 0.1, 0.2, 0.3, 0.1, 0.2\n0.1, 0.2, 0.3, 0.1, 0.2, 0.3, 0.1, 0.2\n0.1, nan, 0.3, 0.1, 0.2, 0.3, 0.1, 0.2\n' >scan.csv; sed -i 's/^relief_mm = /scan = \"scan.csv\"\nrelief_mm = /' texture.toml"
broken "a scan row of another length" scan.csv 2 height "printf '0.1 0.2 0.3 0.1 0.2 0.3 0.1 0.2\n0.1 0.2 0.3\n' >scan.csv; sed -i 's/^relief_mm = /scan = \"scan.csv\"\nrelief_mm = /' texture.toml"
broken "a material out of range" soil_copy.toml '^mass_kg = ' probe.mass_kg "sed 's/^mass_kg = .*/mass_kg = 500.0/' '$textures/materials/dry_soil.toml' >soil_copy.toml; sed -i 's/^material = .*/material = \"soil_copy\"/' texture.toml"
broken "an unknown material" texture.toml '^material = ' material "sed -i 's/^material = .*/material = \"unobtainium\"/' texture.toml"
broken "a relief out of range" texture.toml '^relief_mm = ' relief_mm "sed -i 's/^relief_mm = .*/relief_mm = 50.0/' texture.toml"
broken "a trim out of range" texture.toml '^sound_trim_db = ' gains.sound_trim_db "sed -i 's/^sound_trim_db = .*/sound_trim_db = 40.0/' texture.toml"
broken "a missing cue" texture.toml '^de = \"trockenes' cues "rm cues/de/${key}_name.wav"
broken "a silent cue" "cues/it/${key}_description.wav" 1 cue "sox -n -r 48000 -c 1 cues/it/${key}_description.wav trim 0 2"
broken "a TOML syntax error" texture.toml '^\[gains' syntax "sed -i 's/^\[gains\]/[gains/' texture.toml"

# Nothing is installed from a bad folder.
staff=$work/staff
mkdir -p "$staff"
"$app" texture install "$work/case1/$key" --staff-dir "$staff" >"$work/install.log" 2>&1
rc=$?
if [ $rc != 1 ]; then
  fail "install of a broken folder: exit $rc, want 1"
elif [ -e "$staff/textures/$key" ] || [ -n "$(ls -A "$staff")" ] && [ -n "$(ls -A "$staff/textures" 2>/dev/null)" ]; then
  fail "install of a broken folder left files in $staff"
else
  echo "ok: install of a broken folder exits 1 and installs nothing ($(tail -1 "$work/install.log"))"
fi
# A curator with a private umask (and a folder only they can read) installs a texture the kiosk's
# own user can still read: every directory 755, every file 644.
chmod -R go-rwx "$good"
(umask 077 && "$app" texture install "$good" --staff-dir "$staff" >"$work/install_good.log" 2>&1)
rc=$?
if [ $rc != 0 ]; then
  sed 's/^/    /' "$work/install_good.log"
  fail "install of the good folder under umask 077: exit $rc"
else
  modes=$(cd "$staff" && find textures -printf '%y %m %p\n' | sort)
  if bad=$(echo "$modes" | awk '($1 == "d" && $2 != "755") || ($1 == "f" && $2 != "644")') && [ -n "$bad" ]; then
    fail "installed under umask 077, not readable by the kiosk's user: $(echo "$bad" | head -3 | paste -sd';' -)"
  else
    echo "ok: installed under umask 077, $(echo "$modes" | wc -l) entries all 755 (folders) or 644 (files)"
  fi
fi
echo "$n broken folders checked, $failures failures"
[ $failures = 0 ]
