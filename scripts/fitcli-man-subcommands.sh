#!/usr/bin/env bash
# The SUBCOMMANDS section of fitcli's man page (help2man --include): one subsection per
# subcommand and nested subcommand (surface fit, ...), each the subcommand's own --help as
# printed, so the page cannot drift from the program (docs/cli.md "Man page and completion").
# Arguments: FITCLI OUT.
set -euo pipefail
fitcli=$1
out=$2
# The names under "Subcommands:" in a --help text.
subcommands() { awk '/^Subcommands:/ {on = 1; next} on && /^  [a-z]/ {print $1} on && /^$/ {on = 0}'; }
# A help text as roff between .nf and .fi: backslashes and leading dots or quotes escaped, the
# program's path as plain "fitcli".
roff() {
  sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/" -e 's/-/\\-/g' -e 's#^Usage: .*fitcli#Usage: fitcli#'
}
section() {  # words of the subcommand, e.g. "surface fit"
  local help
  # shellcheck disable=SC2086  # the words of a nested subcommand
  help=$("$fitcli" $1 --help)
  printf '.SS "fitcli %s"\n.nf\n' "$(sed 's/-/\\-/g' <<<"$1")"
  roff <<<"$help"
  printf '.fi\n'
  local sub
  for sub in $(subcommands <<<"$help"); do section "$1 $sub"; done
}
{
  printf '[SUBCOMMANDS]\n'
  printf 'Each subcommand'"'"'s options, as \\fBfitcli SUBCOMMAND \\-\\-help\\fR prints them.\n'
  for sub in $("$fitcli" --help | subcommands); do section "$sub"; done
} >"$out.tmp"
mv "$out.tmp" "$out"
