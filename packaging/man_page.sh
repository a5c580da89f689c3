#!/usr/bin/env bash
# Writes the manual page penink(1) from the program's own help, so the page lists every
# subcommand and option the binary has. Usage: man_page.sh PENINK_BINARY OUT.1 VERSION
# The fixed parts (description, layers, exit status, files, examples) are in penink.1.head and
# penink.1.tail beside this script; each subcommand's `penink SUB --help` becomes a section
# with one tagged paragraph per option.
set -euo pipefail
bin=$1 out=$2 version=$3
here=$(cd "$(dirname "$0")" && pwd)

# Troff-safe text: backslashes, and a leading . or ' that would read as a request.
esc() { sed -e 's/\\/\\e/g' -e "s/^\([.']\)/\\\\\&\1/"; }

# One subcommand's help as troff: its description, usage, then .TP per positional/option.
# CLI11 prints "  TERM   description" with continuation lines indented to the description.
section() {
    local sub=$1
    "$bin" "$sub" --help | esc | awk -v cmd="$sub" '
        function flush() { if (term != "") { printf ".TP\n\\fB%s\\fR\n%s\n", term, desc }; term = ""; desc = "" }
        NR == 1 { printf ".SS \"penink %s\"\n%s\n", cmd, $0; next }
        /^Usage:/ { flush(); sub(/^Usage: [^ ]*penink/, "penink"); printf ".PP\n.B %s\n", $0; next }
        /^(Positionals|Options):/ { flush(); printf ".PP\n%s\n", $0; next }
        /^  [^ ]/ {
            flush()
            line = substr($0, 3)
            i = match(line, /  +/)
            if (i) { term = substr(line, 1, i - 1); desc = substr(line, i + RLENGTH) } else { term = line; desc = "" }
            gsub(/-/, "\\-", term)
            next
        }
        /^   +[^ ]/ { sub(/^ +/, ""); desc = (desc == "" ? $0 : desc " " $0); next }
        /^[ \t]*$/ { next }
        { flush(); print }
        END { flush() }'
}

subs=$("$bin" --help | awk '/^Subcommands:/ { on = 1; next } on && /^  [^ ]/ { print $1 } on && /^[^ ]/ { on = 0 }')
[[ -n $subs ]] || { echo "man_page.sh: no subcommands in '$bin --help'" >&2; exit 1; }
{
    sed -e "s/@VERSION@/$version/" -e "s/@DATE@/$(date -u -d "@${SOURCE_DATE_EPOCH:-$(date +%s)}" +%Y-%m-%d)/" "$here/penink.1.head"
    echo ".SH COMMANDS"
    for s in $subs; do section "$s"; done
    cat "$here/penink.1.tail"
} >"$out.tmp"
mv "$out.tmp" "$out"
