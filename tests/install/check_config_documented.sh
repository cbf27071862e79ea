#!/usr/bin/env bash
# Every key of the shipped example configuration (install/kiosk.toml, which the kiosk_config tests
# keep equal to the built-in defaults) has a row in README's configuration table: `table.key`.
#   check_config_documented.sh <README.md> <kiosk.toml>
set -euo pipefail
readme="$1"
config="$2"
table=""
count=0
missing=0
while IFS= read -r line; do
  line="${line%%#*}"
  if [[ "$line" =~ ^[[:space:]]*\[([A-Za-z0-9_]+)\][[:space:]]*$ ]]; then
    table="${BASH_REMATCH[1]}"
  elif [[ "$line" =~ ^[[:space:]]*([A-Za-z0-9_]+)[[:space:]]*= ]]; then
    key="$table.${BASH_REMATCH[1]}"
    count=$((count + 1))
    if ! grep -qF "| \`$key\` |" "$readme"; then
      echo "MISSING in README: $key"
      missing=1
    fi
  fi
done < "$config"
[ "$count" -gt 0 ] || { echo "FAIL: no keys read from $config"; exit 1; }
[ "$missing" -eq 0 ] || exit 1
echo "all $count keys of $(basename "$config") are documented"
