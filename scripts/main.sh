#!/usr/bin/env bash
# The main job on built-in defaults: candidate-direction summaries for orders 3..8.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
for order in 3 4 5 6 7 8; do
  "$ZHF_BUILD/cli/zhf" candidates --order "$order"
done
