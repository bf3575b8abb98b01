# Bash completion of fitcli (installed as share/bash-completion/completions/fitcli): subcommands
# and options are read from fitcli's own --help, so they never drift from the binary.
# Source it (". scripts/fitcli-completion.bash") to try it in a shell.
_fitcli() {
  local cur=${COMP_WORDS[COMP_CWORD]} words=() i
  for ((i = 1; i < COMP_CWORD; ++i)); do
    [[ ${COMP_WORDS[i]} == -* ]] || words+=("${COMP_WORDS[i]}")  # the subcommand path (surface grid)
  done
  local help
  help=$("${COMP_WORDS[0]}" "${words[@]}" --help 2>/dev/null) || help=""
  if [[ $cur == -* ]]; then
    COMPREPLY=($(compgen -W "$(grep -o -- '--[a-z][a-z0-9-]*' <<<"$help" | sort -u)" -- "$cur"))
    return
  fi
  local subcommands
  subcommands=$(awk 'tolower($0) ~ /^subcommands:/ {on = 1; next} on && /^ +[a-z]/ {print $1}' <<<"$help")
  if [[ -n $subcommands ]]; then
    COMPREPLY=($(compgen -W "$subcommands" -- "$cur"))
  else
    COMPREPLY=($(compgen -f -- "$cur"))  # option values: files
  fi
}
complete -o filenames -o bashdefault -F _fitcli fitcli
