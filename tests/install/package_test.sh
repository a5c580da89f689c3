#!/usr/bin/env bash
# CTest Install.DebianPackage. Usage: package_test.sh BUILD_DIR
# Builds the Debian package with CPack, checks its control fields (package, version, the shared
# libraries' packages from dpkg-shlibdeps, OSMesa) and its file list (binary, raster module, man
# page, bash completion, styles, examples), unpacks it into a temporary root with dpkg-deb -x and
# runs the unpacked binary: --help, the manual page through man, a render of the installed
# example to SVG and PNG (checked: layers in the SVG; the PNG's size and resolution), an unknown
# raster extension refused, and the completion script's answers.
set -euo pipefail
build=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/pkg" >"$tmp/cpack.log" 2>&1 || { cat "$tmp/cpack.log"; fail "cpack"; }
deb=$(ls "$tmp"/pkg/penink_*.deb)
version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
[[ $(dpkg-deb -f "$deb" Package) == penink ]] || fail "package name"
[[ $(dpkg-deb -f "$deb" Version) == "$version" ]] || fail "version $(dpkg-deb -f "$deb" Version), want $version"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
for d in libopenimageio2.4 libgdal32 libosmesa6 libdeflate0 libc6 libstdc++6; do
    [[ ", $depends," == *", $d "* || ", $depends," == *", $d,"* ]] || fail "Depends lacks $d"
done

dpkg-deb -c "$deb" | awk '{ print $NF }' | sed 's|^\./|/|' >"$tmp/files"
for f in /usr/bin/penink /usr/lib/penink/penink_oiio.so /usr/lib/penink/penink_mpi.so /usr/share/man/man1/penink.1.gz \
         /usr/share/bash-completion/completions/penink /usr/share/penink/styles/technical.toml \
         /usr/share/penink/styles/field-sketch.toml /usr/share/penink/examples/volcano.toml \
         /usr/share/penink/examples/volcano.asc; do
    grep -qx "$f" "$tmp/files" || fail "$f not in the package"
done
! grep -qE '\.(dv|lod)$' "$tmp/files" || fail "a cache file is in the package"

root=$tmp/root
dpkg-deb -x "$deb" "$root"
penink=$root/usr/bin/penink
help=$("$penink" --help)
for s in render drainage fill batch bench; do grep -qE "^  $s( |$)" <<<"$help" || fail "--help lacks $s"; done

# The manual page: every subcommand has a section, the render options are in it, no troff warning.
man=$(zcat "$root/usr/share/man/man1/penink.1.gz")
[[ $(grep -c '^\.SS "penink ' <<<"$man") -ge 4 ]] || fail "manual page: fewer than 4 subcommand sections"
grep -q '^\\fB\\-o,\\-\\-output ' <<<"$man" || fail "manual page lacks -o,--output"
grep -q 'max\\-memory' <<<"$man" || fail "manual page lacks --max-memory"
warnings=$(zcat "$root/usr/share/man/man1/penink.1.gz" | groff -man -Tutf8 -ww -z 2>&1)
[[ -z $warnings ]] || fail "groff: $warnings"

# A render of the installed example, from a folder of its own (caches go to the user's cache).
mkdir -p "$tmp/work" "$tmp/home"
cd "$tmp/work"
HOME=$tmp/home "$penink" render "$root/usr/share/penink/examples/volcano.toml" --width 160 --height 120 \
    --dpi 192 -o v.svg -o v.png >"$tmp/render.log" 2>&1 || { cat "$tmp/render.log"; fail "render"; }
for l in surface ridges creases silhouettes; do grep -q "inkscape:label=\"$l\"" v.svg || fail "v.svg lacks layer $l"; done
[[ $(head -c 8 v.png | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "v.png is not a PNG"
size=$(od -An -tu1 -j16 -N8 v.png | awk '{ printf "%dx%d", $3 * 256 + $4, $7 * 256 + $8 }')
[[ $size == 320x240 ]] || fail "v.png is $size, want 320x240 (160x120 at 192 dpi)"
grep -q pHYs v.png || fail "v.png has no resolution (pHYs)"
# The installed examples' folder is writable here (root) but under the install prefix: the
# caches went to the user's cache folder.
! ls "$root/usr/share/penink/examples" | grep -qE '\.(dv|lod)$' || fail "a cache was written beside the installed example"
ls "$tmp/home/.cache/penink/"volcano.asc-*.dv >/dev/null 2>&1 || fail "no drainage cache in the user's cache folder"
out=$(HOME=$tmp/home "$penink" render "$root/usr/share/penink/examples/volcano.toml" -o v.gif 2>&1) && fail "v.gif accepted"
[[ $out == 'penink: export: v.gif: unknown output format ".gif"'* ]] || fail "v.gif: $out"

# Bash completion, from the installed script with the installed binary on PATH.
complete_words() {  # complete_words WORD... : the completions of the last word
    PATH=$root/usr/bin:$PATH bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _penink; printf "%s\n" "${COMPREPLY[@]}"' \
        _ "$root/usr/share/bash-completion/completions/penink" "$@" | sort | tr '\n' ' '
}
[[ $(complete_words penink r) == "render " ]] || fail "completion of 'penink r': $(complete_words penink r)"
[[ $(complete_words penink '') == "batch bench drainage fill preview render " ]] || fail "subcommands: $(complete_words penink '')"
[[ $(complete_words penink render --ou) == "--output " ]] || fail "render --ou: $(complete_words penink render --ou)"
[[ $(complete_words penink drainage --rou) == "--routing " ]] || fail "drainage --rou: $(complete_words penink drainage --rou)"
[[ $(complete_words penink render x.toml --gl '') == "egl osmesa " ]] || fail "--gl: $(complete_words penink render x.toml --gl '')"
[[ $(complete_words penink render v.s) == "v.svg " ]] || fail "file names: $(complete_words penink render v.s)"
# Every shipped style is offered by --style and named in the manual's FILES section.
styles_completed=" $(complete_words penink render x.toml --style '') "
manual=$(zcat "$root/usr/share/man/man1/penink.1.gz" | sed 's/\\-/-/g')
for f in "$root"/usr/share/penink/styles/*.toml; do
    name=$(basename "$f" .toml)
    [[ $styles_completed == *" $name "* ]] || fail "--style completion lacks $name: $styles_completed"
    grep -q -- "$name" <<<"$(awk '/^\.SH FILES/,/^\.SH [^F]/' <<<"$manual")" || fail "manual FILES lacks style $name"
done
echo "package test: $(basename "$deb"), $(wc -l <"$tmp/files") entries, installed binary renders SVG and PNG"
