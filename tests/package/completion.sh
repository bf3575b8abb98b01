#!/usr/bin/env bash
# The bash completion offers fitcli's subcommands and a subcommand's options; the man page
# (help2man) names them too. Arguments: FITCLI COMPLETION_SCRIPT MAN_PAGE.
set -euo pipefail
fitcli=$1
# shellcheck disable=SC1090
source "$2"
complete_line() {  # words of a command line, the last one being completed
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  _fitcli
  echo "${COMPREPLY[*]}"
}
got=$(complete_line "$fitcli" "")
for want in eval export fit life sweep surface; do
  [[ " $got " == *" $want "* ]] || { echo "completion of '': no $want in: $got"; exit 1; }
done
got=$(complete_line "$fitcli" ev)
[ "$got" = "eval" ] || { echo "completion of 'ev': $got"; exit 1; }
got=$(complete_line "$fitcli" eval --fr)
[ "$got" = "--frequency-hz" ] || { echo "completion of 'eval --fr': $got"; exit 1; }
got=$(complete_line "$fitcli" surface "")
[[ " $got " == *" grid "* ]] || { echo "completion of 'surface ': $got"; exit 1; }
echo "completion: subcommands, options and nested subcommands"
if command -v help2man >/dev/null; then
  grep -q '^\.TH FITCLI' "$3" && grep -qF 'material\-point' "$3" && grep -qF '\-\-version' "$3" \
    || { echo "man page $3 lacks its title or subcommands"; exit 1; }
  # A subsection per subcommand and nested subcommand, each with its own options.
  subs=$("$fitcli" --help | awk '/^Subcommands:/ {on = 1; next} on && /^  [a-z]/ {print $1}')
  for sub in $subs "surface fit" "surface eval" "surface grid"; do
    grep -qF ".SS \"fitcli ${sub//-/\\-}\"" "$3" || { echo "man page $3 has no section for '$sub'"; exit 1; }
  done
  [ "$(grep -c '^\.SS "fitcli ' "$3")" -ge 18 ] || { echo "man page $3: fewer than 18 subcommand sections"; exit 1; }
  sed -n '/^\.SS "fitcli eval"/,/^\.SS/p' "$3" | grep -qF '\-\-frequency\-hz' ||
    { echo "man page $3: the eval section lacks --frequency-hz"; exit 1; }
  sed -n '/^\.SS "fitcli surface grid"/,/^\.SS/p' "$3" | grep -qF '\-\-surface\-out' ||
    { echo "man page $3: the surface grid section lacks --surface-out"; exit 1; }
  echo "man page: $(wc -l <"$3") lines, $(grep -c '^\.SS "fitcli ' "$3") subcommand sections"
fi
