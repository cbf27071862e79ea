#!/usr/bin/env bash
# Dev-only: fetch the candidate speech engines that Debian 12 ships outside this machine's apt
# sources (SVOX Pico: non-free; MBROLA and its voices: contrib/non-free), plus the ones in main that
# the voice survey compares (flite, pocketsphinx for the English recognition check),
# as .debs through a temporary sources list, and unpack them with dpkg -x into DEST. Nothing is
# installed into the system and the system's apt lists are left alone.
# Usage: fetch_engines.sh DEST [pico|survey]   (pico: only what regenerating the cues needs)
set -euo pipefail
dest="$(mkdir -p "$1" && cd "$1" && pwd)"
what="${2:-survey}"
apt_dir="$dest/apt"
mkdir -p "$apt_dir/lists/partial" "$apt_dir/archives/partial" "$dest/root"
cat > "$apt_dir/sources.list" <<SOURCES
deb http://deb.debian.org/debian bookworm main contrib non-free
SOURCES
apt_opts=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o "Dir::Etc::SourceParts=-"
          -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache::Archives=$apt_dir/archives"
          -o "Dir::Cache::pkgcache=" -o "Dir::Cache::srcpkgcache=" -o "Debug::NoLocking=1")
apt-get "${apt_opts[@]}" -qq update
packages=(libttspico0 libttspico-data)
if [ "$what" = survey ]; then
  packages+=(mbrola mbrola-en1 mbrola-us1 mbrola-us2 mbrola-us3 mbrola-de1 mbrola-de2 mbrola-de3
             mbrola-de4 mbrola-de5 mbrola-de6 mbrola-de7 mbrola-fr1 mbrola-fr2 mbrola-fr3 mbrola-fr4
             mbrola-fr6 mbrola-it1 mbrola-it2 mbrola-it3 mbrola-it4 mbrola-es1 mbrola-es2 mbrola-es3
             mbrola-es4
             flite libflite1 pocketsphinx libpocketsphinx3 libsphinxbase3 pocketsphinx-en-us)
fi
(cd "$apt_dir/archives" && apt-get "${apt_opts[@]}" -qq download "${packages[@]}")
for deb in "$apt_dir"/archives/*.deb; do dpkg -x "$deb" "$dest/root"; done
echo "fetch_engines: ${#packages[@]} packages unpacked into $dest/root"
