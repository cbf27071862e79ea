#!/usr/bin/env bash
# The example alerting rules the package ships pass Prometheus's own checker (promtool, from
# Debian's prometheus package), fire and stay quiet as the unit tests next to this script say
# (promtool test rules), and name every metric they use as the kiosk writes it.
#   check_alert_rules.sh <sketch-a-scratch.rules.yml> <health_metrics.cpp>
set -euo pipefail
rules="$1"
source="$2"
command -v promtool >/dev/null || { echo "FAIL: promtool not installed (install/packages.txt, test group)"; exit 1; }
promtool check rules "$rules"
# The rules' tests name the rules file relative to themselves (the source tree's layout).
(cd "$(dirname "${BASH_SOURCE[0]}")" && promtool test rules sketch-a-scratch.rules.test.yml)
# A renamed metric would leave a rule that never fires, which promtool cannot see.
status=0
for name in $(grep -o 'sketch_a_scratch_[a-z_]*' "$rules" | sort -u); do
  if ! grep -q "\"$name\"" "$source"; then
    echo "FAIL: $rules uses $name, which the kiosk does not write"
    status=1
  fi
done
exit $status
