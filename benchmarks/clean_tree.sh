#!/usr/bin/env bash
# Sourced by the scripts that write benchmarks/results: sets up (scripts/setup.sh), goes to the top of
# the checkout and refuses a tree with changes, tracked or new under bench/ and docs/, since every
# results file names the commit it measured (benchmarks/record.sh).
#   source benchmarks/clean_tree.sh NAME
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cd "$ZHF_ROOT"
if ! git diff --quiet HEAD -- || [ -n "$(git ls-files --others --exclude-standard -- bench docs)" ]; then
  echo "$1: the tree has changes; commit them first (the results name the commit they measured)" >&2
  exit 1
fi
