# bash completion for penink: subcommands, each subcommand's options (read from
# `penink SUB --help`, so they follow the installed binary), the values of the options that take
# a fixed set, and file or folder names elsewhere.
# The option names of a help text: the terms of its lines that start "  -x,--long".
_penink_options() {
    grep -E '^  -' | sed -E 's/^  ([^ ]*).*/\1/' | tr ',' '\n' | grep -E '^--?[A-Za-z]'
}

_penink() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}
    local cmd=${COMP_WORDS[0]} sub="" i
    for ((i = 1; i < COMP_CWORD; i++)); do
        case ${COMP_WORDS[i]} in
            render | drainage | fill | batch | bench | preview) sub=${COMP_WORDS[i]}; break ;;
        esac
    done
    COMPREPLY=()
    if [[ -z $sub ]]; then
        if [[ $cur == -* ]]; then
            COMPREPLY=($(compgen -W "$("$cmd" --help 2>/dev/null | _penink_options)" -- "$cur"))
        else
            COMPREPLY=($(compgen -W "$("$cmd" --help 2>/dev/null | awk '/^Subcommands:/ { on = 1; next } on && /^  [^ ]/ { print $1 } on && /^[^ ]/ { on = 0 }')" -- "$cur"))
        fi
        return
    fi
    case $prev in
        --style)
            COMPREPLY=($(compgen -W "technical field-sketch plotter" -- "$cur") $(compgen -f -X '!*.toml' -- "$cur") $(compgen -d -- "$cur"))
            compopt -o filenames 2>/dev/null
            return ;;
        --gl) COMPREPLY=($(compgen -W "osmesa egl" -- "$cur")); return ;;
        --layers) COMPREPLY=($(compgen -W "kind kind+distance" -- "$cur")); return ;;
        --grid) COMPREPLY=($(compgen -W "none map graticule" -- "$cur")); return ;;
        --routing) COMPREPLY=($(compgen -W "priority-flood least-cost" -- "$cur")); return ;;
        --analytic) COMPREPLY=($(compgen -W "hill two-hills smooth-cliff saddle" -- "$cur")); return ;;
        --page) COMPREPLY=($(compgen -W "A0 A1 A2 A3 A4 A5 A6 B4 B5 letter legal tabloid" -- "$cur")); return ;;
        --out | --rasters | --cache-dir)
            COMPREPLY=($(compgen -d -- "$cur"))
            compopt -o filenames 2>/dev/null
            return ;;
        --width | --height | --dpi | --margin | --seed | --vertical-exaggeration | --sea-level | --scale | --title | --resample | --warmup | --orbit | --port | \
        --max-memory | --frames | --levels | --sizes | --tolerances | --methods | --formats | --needs-size | --ref-edge-px | \
        --ref-supersample)
            return ;;  # a number or a list: nothing to offer
    esac
    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$("$cmd" "$sub" --help 2>/dev/null | _penink_options)" -- "$cur"))
        return
    fi
    COMPREPLY=($(compgen -f -- "$cur"))
    compopt -o filenames 2>/dev/null
}
complete -F _penink penink
